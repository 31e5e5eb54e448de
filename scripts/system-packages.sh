# Installs, only when missing, the Debian packages lightpaint needs to run wgpu on Mesa's
# lavapipe (software Vulkan, for machines without a GPU) and windows under Xvfb, plus the
# screenshot tool the smoke test uses, fontconfig with a font for the study's plot
# (plotters draws text through font-kit), and zenity, which the editor's file dialogs
# fall back to where no desktop portal answers (rfd), driven in the editor's smoke test
# by xdotool; and g++, which builds meshoptimizer (the meshes' levels of detail). Sourced
# by every script here that builds or runs lightpaint.

lightpaint_packages=(
    mesa-vulkan-drivers libvulkan1 xvfb xauth libxkbcommon-x11-0 libx11-xcb1 libxcursor1
    libxrandr2 libxi6 libgl1 libegl1 libwayland-client0 imagemagick x11-apps
    pkg-config libfontconfig-dev fonts-dejavu-core zenity xdotool g++
)

lightpaint_install_system_packages() {
    local missing=() package
    for package in "${lightpaint_packages[@]}"; do
        dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
            || missing+=("$package")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    echo "installing system packages: ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# wgpu and the window system want a private runtime directory.
lightpaint_runtime_dir() {
    if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -w "${XDG_RUNTIME_DIR}" ]; then
        XDG_RUNTIME_DIR="$(mktemp -d)"
        chmod 700 "$XDG_RUNTIME_DIR"
        export XDG_RUNTIME_DIR
    fi
}

# What the scripts that run the built binary need: the packages, a runtime directory and
# the binary, whose path goes to LIGHTPAINT_BIN.
lightpaint_build_to_run() {
    lightpaint_install_system_packages
    lightpaint_runtime_dir
    cargo build --quiet --bin lightpaint
    LIGHTPAINT_BIN="${CARGO_TARGET_DIR}/debug/lightpaint"
}

# Builds go to a fixed directory outside the checkout, so fresh clones reuse them.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/lightpaint-target}"
