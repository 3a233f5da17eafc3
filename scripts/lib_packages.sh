# Sourced by the scripts that install Debian packages (setup.sh, fuzz.sh).
# install_missing WHO PACKAGE...: installs the packages dpkg does not have, as root or with sudo;
# quick when nothing is missing.
install_missing() {
    local who=$1 p missing=() sudo_cmd=()
    shift
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    ((${#missing[@]})) || return 0
    echo "$who: installing ${missing[*]}" >&2
    if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
    export DEBIAN_FRONTEND=noninteractive
    "${sudo_cmd[@]}" apt-get update -qq
    "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}
