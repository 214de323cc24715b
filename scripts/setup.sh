#!/usr/bin/env bash
# Installs what causticlab needs on Debian 12 (idempotent): lavapipe (software Vulkan), the
# Khronos validation layer, the Vulkan loader/headers, vulkaninfo, and the static shaderc/glslang
# that vkcore links (see .cargo/config.toml), DejaVu Sans, the font the bench plots are
# drawn with (crates/bench/src/font.rs), and for the viewer's tests (`causticlab view` under a
# virtual X server) Xvfb, xauth and the X11 libraries winit opens at run time. Checks that cargo
# is there.
set -euo pipefail

packages=(mesa-vulkan-drivers vulkan-validationlayers libvulkan-dev vulkan-tools libshaderc-dev glslang-dev spirv-tools fonts-dejavu-core
    xvfb xauth libx11-6 libx11-xcb1 libxcursor1 libxrandr2 libxi6 libxkbcommon-x11-0)

missing=()
for p in "${packages[@]}"; do
    if ! dpkg -s "$p" >/dev/null 2>&1; then
        missing+=("$p")
    fi
done

if [ "${#missing[@]}" -eq 0 ]; then
    echo "setup: Debian packages already installed: ${packages[*]}"
else
    echo "setup: installing missing Debian packages: ${missing[*]}"
    if [ "$(id -u)" -eq 0 ]; then
        sudo=()
    elif command -v sudo >/dev/null 2>&1; then
        sudo=(sudo)
    else
        echo "setup: not root and no sudo; install as root: apt-get install ${missing[*]}" >&2
        exit 1
    fi
    export DEBIAN_FRONTEND=noninteractive
    "${sudo[@]}" apt-get update
    "${sudo[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
    echo "setup: installed ${missing[*]}"
fi

if ! command -v cargo >/dev/null 2>&1; then
    echo "setup: cargo not found; install Rust with rustup (https://rustup.rs), then rerun" >&2
    exit 1
fi
echo "setup: $(cargo --version)"
