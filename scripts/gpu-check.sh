#!/usr/bin/env bash
# Checks sweepffd on a GPU in one call: the GPU test binaries, then `sweepffd info` and
# `sweepffd bench --json` at 1M, 10M and 100M vertices, into one JSON summary.
#
#   scripts/gpu-check.sh [OUT]          build (cargo), then check; OUT defaults to gpu-check/
#   scripts/gpu-check.sh --package DIR  build and copy the stripped binaries into DIR only
#   scripts/gpu-check.sh --from DIR [OUT]   check with the binaries of --package (no Rust needed)
#
# Environment: SIZES (vertex counts, default "1000000 10000000 100000000"), RUNS (bench runs per
# figure, default 5; 3 at 100M and above), BENCH_TIMEOUT (seconds per bench, default 600).
# OUT/summary.json holds the adapter, each test binary's pass and fail counts and exit status,
# and each bench's JSON line (docs/performance.md, "Checking a GPU", says what to read there).
# Every output of each step is kept beside it in OUT. The script fails if a test fails or a
# bench does not finish; a missing GPU adapter fails the tests (SWEEPFFD_REQUIRE_GPU=1).
set -uo pipefail
cd "$(dirname "$0")/.."

sizes=${SIZES:-"1000000 10000000 100000000"}
runs=${RUNS:-5}
bench_timeout=${BENCH_TIMEOUT:-600}
export SWEEPFFD_REQUIRE_GPU=1
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"

# The release test binaries of the engine's unit tests (src/gpu/tests among them) and of
# tests/gpu, the example tests/gpu runs, and the command-line tool, built by cargo; prints
# "name path" lines.
build() {
    cargo build --release -p sweepffd-cli >&2 || return 1
    cargo test --release -p sweepffd --lib --test gpu --no-run 2>&1 >/dev/null \
        | sed -n 's/.*Executable \(unittests src\/lib.rs\|tests\/gpu\/main.rs\) (\(.*\))/\1 \2/p' \
        | sed 's/^unittests src\/lib.rs/engine/; s/^tests\/gpu\/main.rs/gpu/'
    echo "embed target/release/examples/embed"
    echo "sweepffd target/release/sweepffd"
}

if [ "${1:-}" = "--package" ]; then
    dir=${2:?"--package needs a folder"}
    # Cargo's layout: a test finds the example it runs at ../examples from its own folder.
    mkdir -p "$dir/deps" "$dir/examples"
    build | while read -r name path; do
        case $name in
            engine | gpu) target=$dir/deps/$name ;;
            embed) target=$dir/examples/embed ;;
            *) target=$dir/$name ;;
        esac
        cp "$path" "$target" && strip "$target" && echo "$target"
    done
    exit 0
fi

if [ "${1:-}" = "--from" ]; then
    bin=${2:?"--from needs the folder of --package"}
    out=${3:-gpu-check}
    binaries="engine $bin/deps/engine
gpu $bin/deps/gpu
sweepffd $bin/sweepffd"
else
    out=${1:-gpu-check}
    binaries=$(build) || { echo "error: the build failed" >&2; exit 1; }
fi
mkdir -p "$out"
path_of() { echo "$binaries" | awk -v name="$1" '$1 == name { print $2 }'; }
sweepffd=$(path_of sweepffd)
status=0

"$sweepffd" info > "$out/info.txt" 2>&1 || status=1
adapter=$(sed -n 's/^adapter: *//p' "$out/info.txt" | head -n 1)
adapter_type=$(sed -n 's/^type: *//p' "$out/info.txt" | head -n 1)
records=$(sed -n 's/^cell records (auto): *//p' "$out/info.txt" | head -n 1)
echo "adapter: $adapter ($adapter_type)"

tests_json=""
for name in engine gpu; do
    binary=$(path_of "$name")
    echo "--- tests: $name"
    start=$(date +%s)
    "$binary" --test-threads 4 > "$out/tests-$name.txt" 2>&1
    rc=$?
    passed=$(grep -c '\.\.\. ok$' "$out/tests-$name.txt")
    failed=$(grep -c '\.\.\. FAILED$' "$out/tests-$name.txt")
    echo "$passed passed, $failed failed, exit $rc, $(( $(date +%s) - start )) s"
    [ "$rc" = 0 ] || status=1
    tests_json+="${tests_json:+,}{\"binary\":\"$name\",\"passed\":$passed,\"failed\":$failed,\"rc\":$rc}"
done

bench_json=""
for n in $sizes; do
    r=$runs
    if [ "$n" -ge 100000000 ] && [ "$r" -gt 3 ]; then r=3; fi
    echo "--- bench: $n vertices, $r runs"
    start=$(date +%s)
    timeout "$bench_timeout" "$sweepffd" bench --backend gpu --vertices "$n" --runs "$r" --json \
        > "$out/bench-$n.json" 2> "$out/bench-$n.txt"
    rc=$?
    echo "exit $rc, $(( $(date +%s) - start )) s"
    if [ "$rc" = 0 ]; then
        bench_json+="${bench_json:+,}$(cat "$out/bench-$n.json")"
    else
        status=1
        bench_json+="${bench_json:+,}{\"n\":$n,\"rc\":$rc,\"error\":\"see bench-$n.txt\"}"
    fi
done

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
printf '{"date":"%s","commit":"%s","adapter":"%s","type":"%s","cell_records":"%s","tests":[%s],"bench":[%s]}\n' \
    "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$commit" "$adapter" "$adapter_type" "$records" "$tests_json" "$bench_json" \
    > "$out/summary.json"
echo "summary: $out/summary.json"
exit $status
