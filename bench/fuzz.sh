#!/usr/bin/env bash
# Fuzzes the LEF, DEF and guide readers with libFuzzer (clang + AddressSanitizer).
#
#   bash bench/fuzz.sh [SECONDS_PER_TARGET]     (default 60)
#
# Needs clang with its libFuzzer runtime (Debian: clang-14 libclang-rt-14-dev).
# Seeds come from the small contest testcases and tests/fuzz_regressions/.
# Any input that crashes, hangs or leaks lands in build/fuzz/artifacts/;
# turn each into a regression file under tests/fuzz_regressions/<target>/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
secs=${1:-60}
data=${XROUTE_TESTCASES:-$root/../shared/testcases}
data=${data%%:*}
cxx=${CXX_FUZZ:-$(command -v clang++ || command -v clang++-14 || true)}
[ -n "$cxx" ] || { echo "fuzz.sh: clang++ not found (apt-get install clang-14 libclang-rt-14-dev)" >&2; exit 2; }
[ -d "$data/ispd18_sample" ] || { echo "fuzz.sh: testcases not found in $data" >&2; exit 2; }

build=$root/build/fuzz
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DXROUTE_PYTHON=OFF -DXROUTE_FUZZ=ON >/dev/null
ninja -C "$build" fuzz_lef fuzz_def fuzz_guide >/dev/null

s=$data/ispd18_sample/ispd18_sample.input
s2=$data/ispd18_sample2/ispd18_sample2.input
mkdir -p "$build"/corpus/{lef,def,guide} "$build/artifacts"
cp -f "$s.lef" "$s2.lef" "$build/corpus/lef/"
cp -f "$s.def" "$s2.def" "$build/corpus/def/"
cp -f "$s.guide" "$build/corpus/guide/"
for t in lef def guide; do
  if [ -d "$root/tests/fuzz_regressions/$t" ]; then cp -f "$root/tests/fuzz_regressions/$t"/* "$build/corpus/$t/" 2>/dev/null || true; fi
done

export XROUTE_FUZZ_LEF=$s.lef XROUTE_FUZZ_DEF=$s.def
export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
status=0
for t in lef def guide; do
  log=$build/fuzz_$t.log
  echo "== fuzz_$t: ${secs}s"
  if "$build/fuzz_$t" "$build/corpus/$t" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
      -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/artifacts/$t-" >"$log" 2>&1; then
    echo "   ok: $(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}') runs," \
         "$(ls "$build/corpus/$t" | wc -l) corpus files, no crash"
  else
    status=1
    echo "   FAILED (see $log):"
    grep -E 'ERROR|SUMMARY|Test unit written' "$log" | head -5 | sed 's/^/   /'
  fi
done
exit $status
