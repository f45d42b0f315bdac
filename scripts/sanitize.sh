#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run of the core unit tests and the filters'
# input tests (after `bash scripts/setup.sh test` has installed the packages):
#   bash scripts/sanitize.sh [build-dir]      (default: build-asan; about 5 minutes on 2 cores)
# Any sanitizer report (memory error, leak, undefined behaviour) fails the run.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build-asan}"
flags="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
env -u DISPLAY cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
  -DCMAKE_SHARED_LINKER_FLAGS="$flags" -DCMAKE_MODULE_LINKER_FLAGS="$flags"
targets=(GeodesicShapesCoreTests TestCrossFieldInputs TestSVGGeodesicDistanceInputs
  TestGeodesicPolarCoordinatesInputs TestMSDTSourceInputs TestSVGGeodesicDistanceSolvers
  TestShapeDistributorInputs)
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1
cd "$build"
ctest --output-on-failure -R "^(Core\.[A-Z][A-Za-z]*\.|GeodesicShapes\.Test(CrossField|SVGGeodesicDistance|GeodesicPolarCoordinates|MSDTSource|ShapeDistributor)Inputs|GeodesicShapes\.TestSVGGeodesicDistanceSolvers)" -E "Against|Accuracy|Extract"
