# Sourced by the scripts in pipelines/: finds the plugin in the build tree, building it (and
# installing the Debian packages it needs) when it is not there yet, so every script runs on
# a fresh machine. GESTURECAM_BUILD_DIR names another build folder (default: build).
gesturecam_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
gesturecam_build=${GESTURECAM_BUILD_DIR:-$gesturecam_root/build}

# Builds the given targets (default: everything) in the build folder, setting it up first
# if needed; an existing build keeps its options.
gesturecam_build_targets() {
  . "$gesturecam_root/tests/deps.sh"
  gesturecam_install_deps
  [ -f "$gesturecam_build/build.ninja" ] || meson setup "$gesturecam_build" "$gesturecam_root" -Dbuildtype=release
  meson compile -C "$gesturecam_build" "$@"
}

# GST_PLUGIN_PATH on the build's plugin; builds it first when it is missing.
gesturecam_use_plugin() {
  [ -f "$gesturecam_build/gst-plugin/libgstgesturecam.so" ] || gesturecam_build_targets gstgesturecam
  export GST_PLUGIN_PATH="$gesturecam_build/gst-plugin${GST_PLUGIN_PATH:+:$GST_PLUGIN_PATH}"
}
