#!/usr/bin/env bash
# Opens the lightpaint editor on the bundled sample (or on the file given), installing the
# system packages needed to run on a machine without a GPU first.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/system-packages.sh
lightpaint_install_system_packages
lightpaint_runtime_dir
exec cargo run --locked --bin lightpaint -- "$@"
