# Sourced by tests/run.sh and pipelines/demo.sh: installs the Debian 12 packages the
# project needs, only those that are missing.
GESTURECAM_PACKAGES=(
  meson ninja-build pkg-config g++ clang libclang-rt-14-dev
  libopencv-dev libopencv-contrib-dev libeigen3-dev opencv-doc
  libgstreamer1.0-dev libgstreamer-plugins-base1.0-dev
  gstreamer1.0-tools gstreamer1.0-plugins-base gstreamer1.0-plugins-good gstreamer1.0-plugins-ugly
  gstreamer1.0-libav time
  libgtest-dev valgrind python3
  gobject-introspection libgirepository1.0-dev python3-gi gir1.2-gst-plugins-base-1.0
  libcli11-dev libsoup-3.0-dev libxml2-dev
)

gesturecam_install_deps() {
  local missing=()
  local p
  for p in "${GESTURECAM_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "Installing missing packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# meson setup, or reconfigure an existing build directory with the same options.
gesturecam_setup() {
  local dir=$1; shift
  if [ -f "$dir/build.ninja" ]; then
    meson setup --reconfigure "$dir" "$@" >/dev/null
  else
    meson setup "$dir" "$@"
  fi
}
