# Sourced by the scripts: ensure_packages PKG... installs the Debian packages that are missing
# (as root, or with sudo), and nothing when all are there.
ensure_packages() {
  local missing=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "seedcal: installing ${missing[*]}"
    local sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
}

# The sanitizer + fuzzer build (preset asan) is compiled with clang.
sanitizer_packages=(clang libclang-rt-14-dev libomp-14-dev)
