// Memory hints: prefetching, and handing freed heap blocks back to the system (neither changes
// any result).
#pragma once

namespace gs
{

// A memory hint: load the cache line holding p.
inline void Prefetch(const void* p)
{
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  // (An asm statement: GCC deletes loops holding nothing but __builtin_prefetch.)
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#elif defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

// Blocks freed inside the heap stay resident until they are handed back to the system: builds
// that free many small blocks (per-vertex lists, hash map nodes) before allocating large arrays
// call this between the two. (The saddle vertex graph's build hands freed memory back after
// each slab of its gathering: its peak at 711K vertices with reached stencils went from 3.9 KB
// to 2.1 KB per vertex.)
void ReturnFreedMemory();

} // namespace gs
