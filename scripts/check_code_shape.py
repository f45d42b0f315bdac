#!/usr/bin/env python3
"""Checks the shape of the code under Filters/: no function body longer than --max-function lines,
no source file longer than --max-file lines and, with --stages, no include that runs back up the
core's stages. Prints every offender and exits with 1 when there is one.

Functions are found by brace matching on the source with comments and string literals removed: a
'{' at namespace or class scope whose head has a parameter list opens a function body; lambdas and
local classes count toward the function that holds them."""
import argparse
import os
import re
import sys

SOURCE_SUFFIXES = ('.cpp', '.cxx', '.h')


def strip_comments_and_strings(src):
    """Returns src with comments and string/char literals emptied, keeping every newline."""
    out = []
    i, n = 0, len(src)
    while i < n:
        if src.startswith('//', i):
            j = src.find('\n', i)
            i = n if j < 0 else j
            continue
        if src.startswith('/*', i):
            j = src.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append('\n' * src.count('\n', i, j))
            i = j
            continue
        raw = re.match(r'R"([^(\s]*)\(', src[i:i + 20]) if src[i] == 'R' and (i == 0 or not (src[i - 1].isalnum() or src[i - 1] == '_')) else None
        if raw:
            end = ')' + raw.group(1) + '"'
            j = src.find(end, i)
            j = n if j < 0 else j + len(end)
            out.append('""' + '\n' * src.count('\n', i, j))
            i = j
            continue
        c = src[i]
        if c in '"\'':
            j = i + 1
            while j < n and src[j] != c and src[j] != '\n':
                j += 2 if src[j] == '\\' else 1
            out.append(c + c)
            i = j + 1
            continue
        out.append(c)
        i += 1
    return ''.join(out)


SCOPE_KEYWORDS = re.compile(r'\b(namespace|class|struct|enum|union)\b')
ENDS_LIKE_SIGNATURE = re.compile(r'\)\s*(const)?\s*(noexcept)?\s*(override|final)?\s*(->[^{]*)?$')
CONTROL = re.compile(r'^(if|for|while|switch|catch|do|else)\b')


def long_functions(path, limit):
    """Yields (lines, first line, name) of each function body in path longer than limit lines."""
    with open(path, encoding='utf-8', errors='replace') as f:
        s = strip_comments_and_strings(f.read())
    stack = []  # (kind, first line, name); kind is 'scope', 'function' or 'block'
    head_start, line = 0, 1
    for i, c in enumerate(s):
        if c == '\n':
            line += 1
        elif c == '{':
            head = ' '.join(s[head_start:i].split())
            if any(kind == 'function' for kind, _, _ in stack):
                kind = 'block'
            elif SCOPE_KEYWORDS.search(head) and not ENDS_LIKE_SIGNATURE.search(head):
                kind = 'scope'
            elif '(' in head and not head.endswith('=') and not CONTROL.match(head.split(':')[-1].strip()):
                kind = 'function'
            else:
                kind = 'block'
            names = re.findall(r'([~\w:]+)\s*\(', head)
            stack.append((kind, line, names[0] if names else head[-40:]))
            head_start = i + 1
        elif c == '}':
            if stack:
                kind, first, name = stack.pop()
                if kind == 'function' and line - first + 1 > limit:
                    yield line - first + 1, first, name
            head_start = i + 1
        elif c == ';':
            head_start = i + 1


INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def stage_offenders(core, stages):
    """Includes in core/<stage>/ of a header that lives in a later stage's folder (stages are
    listed first to last: each may use its own and the earlier ones'), and files of core/ that
    are in no stage's folder."""
    home = {}
    for rank, stage in enumerate(stages):
        folder = os.path.join(core, stage)
        if not os.path.isdir(folder):
            yield f'stage folder {folder} is missing'
            continue
        for name in os.listdir(folder):
            home[name] = rank
    for name in sorted(os.listdir(core)):
        if name.endswith(SOURCE_SUFFIXES):
            yield f'file {os.path.join(core, name)}: in no stage folder ({", ".join(stages)})'
    for rank, stage in enumerate(stages):
        folder = os.path.join(core, stage)
        if not os.path.isdir(folder):
            continue
        for name in sorted(os.listdir(folder)):
            if not name.endswith(SOURCE_SUFFIXES):
                continue
            with open(os.path.join(folder, name), encoding='utf-8', errors='replace') as f:
                for header in INCLUDE.findall(f.read()):
                    used = home.get(os.path.basename(header))
                    if used is not None and used > rank:
                        yield (f'include {stage}/{name} -> {stages[used]}/{header}: runs back up '
                               f'the stages ({" -> ".join(stages)})')


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('roots', nargs='+', help='folders to scan')
    parser.add_argument('--max-function', type=int, default=120)
    parser.add_argument('--max-file', type=int, default=900)
    parser.add_argument('--core', help='the core folder whose subfolders are the stages')
    parser.add_argument('--stages', nargs='*', default=[],
                        help='the core\'s stage folders, first to last')
    args = parser.parse_args()
    offenders = []
    for root in args.roots:
        for folder, _, files in sorted(os.walk(root)):
            for name in sorted(files):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                path = os.path.join(folder, name)
                with open(path, encoding='utf-8', errors='replace') as f:
                    lines = sum(1 for _ in f)
                if lines > args.max_file:
                    offenders.append(f'file {path}: {lines} lines (at most {args.max_file})')
                for length, first, function in long_functions(path, args.max_function):
                    offenders.append(f'function {function} at {path}:{first}: {length} lines '
                                     f'(at most {args.max_function})')
    if args.core and args.stages:
        offenders.extend(stage_offenders(args.core, args.stages))
    for offender in offenders:
        print(offender)
    print(f'{len(offenders)} offender(s)')
    return 1 if offenders else 0


if __name__ == '__main__':
    sys.exit(main())
