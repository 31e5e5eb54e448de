#!/usr/bin/env bash
# Runs every lightpaint check and test on a Debian machine, with or without a GPU:
# installs the system packages it needs, then formatting, clippy, doctests and the whole
# test suite (GPU tests on lavapipe, the editor smoke test under Xvfb). Prints the total
# time at the end. LIGHTPAINT_NO_GPU=1 says explicitly that GPU tests should not run.
set -euo pipefail
started=$(date +%s)
trap 'echo "total time: $(( $(date +%s) - started )) s"' EXIT
cd "$(dirname "$0")/.."
source scripts/system-packages.sh
lightpaint_install_system_packages
lightpaint_runtime_dir

cargo fmt --check
cargo clippy --locked --all-targets -- -D warnings
cargo test --locked --doc
# The API docs build without broken or private links.
RUSTDOCFLAGS="-D warnings" cargo doc --locked --no-deps --lib
if cargo nextest --version >/dev/null 2>&1; then
    cargo nextest run --locked --no-fail-fast
else
    cargo test --locked --no-fail-fast
fi
