#!/usr/bin/env bash
# Assembles the QEMU guest of the socketcan tests in GUEST_DIR (a folder of the build tree):
#   GUEST_DIR/vmlinuz      Debian's kernel, from the package scripts/guest-kernel names
#                          (scripts/install-deps downloads it into apt's archive cache;
#                          nothing is installed on the host)
#   GUEST_DIR/initrd.img   our init (guest_init.cpp) and the modules it loads, in /modules with
#                          their load order, dependencies first, read from each module's
#                          depends= string
#   GUEST_DIR/missing      instead of the two, when the kernel package is not there: why, for
#                          qemu_run.sh to fail the tests with (the build itself goes on)
#   guest_image.sh GUEST_DIR INIT_BINARY
# Does nothing when the image is already made from the same package and init.
set -euo pipefail
guest=$1
init=$2
mkdir -p "$guest"
rm -f "$guest/missing"

missing() {
  echo "$*" > "$guest/missing"
  rm -f "$guest/vmlinuz" "$guest/initrd.img" "$guest/stamp"
  echo "guest_image: $*" >&2
  exit 0
}

guest_kernel="$(dirname "$0")/../../scripts/guest-kernel"
package=$("$guest_kernel" name)
[ -n "$package" ] || missing "the kernel package's name cannot be read" \
  "(apt-cache depends linux-image-amd64 names no linux-image-*-amd64): run scripts/install-deps"
# The kernel tree (its boot/ and lib/modules/) stays in the build tree, for the next build;
# .from names the package file it came from.
tree="$guest/kernel"
deb=$("$guest_kernel" deb)
if [ -n "$deb" ]; then
  from=$(basename "$deb")
elif [ -f "$tree/.from" ] && [[ $(cat "$tree/.from") == "${package}"_* ]]; then
  from=$(cat "$tree/.from")  # apt's cache was cleaned since; the tree unpacked from it stays good
else
  missing "$package is not in /var/cache/apt/archives: run scripts/install-deps"
fi

stamp="$from $(sha256sum "$init" | cut -d' ' -f1) $(sha256sum "$0" | cut -d' ' -f1)"
if [ -f "$guest/stamp" ] && [ "$(cat "$guest/stamp")" = "$stamp" ] && [ -f "$guest/initrd.img" ] &&
   [ -f "$guest/vmlinuz" ]; then
  exit 0
fi

if [ ! -f "$tree/.from" ] || [ "$(cat "$tree/.from")" != "$from" ]; then
  rm -rf "$tree"
  mkdir -p "$tree"
  dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$tree" --wildcards './boot/vmlinuz-*' './lib/modules/*'
  basename "$deb" > "$tree/.from"
fi
release=$(ls "$tree/lib/modules" | head -1)
kernel_dir="$tree/lib/modules/$release/kernel"

# Modules by name (a module's name has "_" where its file may have "-"); those built into
# the kernel need no file.
declare -A path_of builtin
while IFS= read -r -d '' f; do
  name=$(basename "$f" .ko)
  path_of[${name//-/_}]=$f
done < <(find "$kernel_dir" -name '*.ko' -print0)
if [ -f "$tree/lib/modules/$release/modules.builtin" ]; then
  while IFS= read -r f; do
    name=$(basename "$f" .ko)
    builtin[${name//-/_}]=1
  done < "$tree/lib/modules/$release/modules.builtin"
fi

# Dependencies first (depth first on depends=), each once.
order=()
declare -A placed
place() {
  local name=${1//-/_} dep deps
  [ -z "${placed[$name]:-}" ] && [ -z "${builtin[$name]:-}" ] || return 0
  [ -n "${path_of[$name]:-}" ] || missing "module $name is not in $package (as a .ko file)"
  placed[$name]=1
  deps=$(strings "${path_of[$name]}" | sed -n 's/^depends=//p' | head -1)
  for dep in ${deps//,/ }; do
    place "$dep"
  done
  order+=("$name")
}
# virtio-pci and 9p for the host's root; can-raw, can-bcm and vcan for the buses.
for root in virtio_pci 9pnet_virtio 9p vcan can_raw can_bcm; do
  place "$root"
done

staging="$guest/initramfs"
rm -rf "$staging"
mkdir -p "$staging/modules" "$staging/newroot" "$staging/proc"
cp "$init" "$staging/init"
for name in "${order[@]}"; do
  cp "${path_of[$name]}" "$staging/modules/$name.ko"
  echo "$name.ko" >> "$staging/modules/order"
done
(cd "$staging" && find . | sort | cpio --quiet -o -H newc) > "$guest/initrd.img.new"
mv "$guest/initrd.img.new" "$guest/initrd.img"
cp "$tree/boot/vmlinuz-$release" "$guest/vmlinuz"
rm -rf "$staging"
echo "$stamp" > "$guest/stamp"
echo "guest_image: $package ($release), ${#order[@]} modules: ${order[*]}"
