#!/usr/bin/env bash
# Runs each fuzz target for a bounded time (default 43 seconds each) and stops at the first failure,
# whose minimised reproducer the fuzzer writes to fixtures/fuzz/. Usage:
#   scripts/fuzz.sh [SECONDS] [SEED]        e.g. scripts/fuzz.sh 3600 7 for an hour per target
# The differential check at scale is: cargo run --release --example fuzz -- --target document --steps 100000
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-43}"
seed="${2:-$(date +%s)}"
cargo build --release --example fuzz
for target in parser analysis document cli config framing publish; do
    echo "== fuzz --target $target --seconds $seconds --seed $seed"
    ./target/release/examples/fuzz --target "$target" --seconds "$seconds" --seed "$seed"
done
