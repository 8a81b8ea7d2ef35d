# Sourced by the security benches, with the build directory as $1: sets `build`, `here` (the
# source tree) and `tmp` (a directory removed at exit), and defines secured_machine.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# secured_machine BUILD BASE.yaml DIR MIDDLEWARE PROTECTION writes DIR/m.yaml, BASE on
# MIDDLEWARE, and for a PROTECTION other than `off` its identities by `mcnc certs --protection
# PROTECTION` in DIR/certs, named by the machine's security_dir.
secured_machine() {
  local build=$1 base=$2 dir=$3 middleware=$4 protection=$5
  mkdir -p "$dir"
  sed "s|^machine:|machine:\n  middleware: $middleware|" "$base" > "$dir/m.yaml"
  if [ "$protection" != off ]; then
    "$build/bin/mcnc" certs "$dir/m.yaml" "$dir/certs" --protection "$protection" > /dev/null
    sed -i "s|^machine:|machine:\n  security_dir: certs|" "$dir/m.yaml"
  fi
}
