# The cross targets of tools/setup.sh and tools/cross-check.sh (sourced by
# both): zs_cross_target TARGET prints its Debian architecture, compiler
# triplet, qemu-user program and Debian's library directory name.
zs_cross_target() {
  case "$1" in
    aarch64) echo "arm64 aarch64-linux-gnu qemu-aarch64-static aarch64-linux-gnu" ;;
    s390x) echo "s390x s390x-linux-gnu qemu-s390x-static s390x-linux-gnu" ;;
    i686) echo "i386 i686-linux-gnu qemu-i386-static i386-linux-gnu" ;;
    musl) echo "- musl-gcc - -" ;; # x86-64 with musl's C library, run as it is
    windows) echo "- x86_64-w64-mingw32 /usr/lib/wine/wine64 -" ;; # mingw-w64, run under wine
    *) echo "unknown cross target '$1' (aarch64, s390x, i686, musl, windows)" >&2; return 1 ;;
  esac
}
