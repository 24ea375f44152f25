#!/bin/sh
# tools/install.sh -- make install and make uninstall (see the Makefile).
#
#   sh tools/install.sh install ROOT VERSION MAJOR
#   sh tools/install.sh uninstall ROOT
#
# ROOT is $(DESTDIR)$(PREFIX).  install copies the built files under ROOT
# and writes ROOT/share/afv/installed: every file and every directory it
# created (directories that existed before are not listed), one per line,
# "file PATH" or "dir PATH", PATH relative to ROOT ("up K" for the K-th
# parent of ROOT, when install had to create ROOT's parents too).
# uninstall removes exactly what that list names: the files, then the
# directories, deepest first, each only if empty (a file someone else put
# there keeps its directory, with a line saying so).
set -eu

MANIFEST=share/afv/installed

die() { echo "tools/install.sh: $*" >&2; exit 2; }

# ---- install ----------------------------------------------------------------
# Directories: record each one created, parents before children.
created_dirs=""
record_dir() { created_dirs="$created_dirs
$1"; }

# ROOT itself and the parents it lacks, recorded as "up K" (K = 0: ROOT).
make_root() {
  missing="" dir=$ROOT k=0
  while [ ! -d "$dir" ]; do
    missing="$k $missing"
    dir=$(dirname "$dir") k=$((k + 1))
  done
  [ -z "$missing" ] && return 0
  mkdir -p "$ROOT"
  for k in $missing; do record_dir "up $k"; done
}

# A directory under ROOT (relative path) and its missing parents.
make_dir() {
  path="" rest=$1
  while [ -n "$rest" ]; do
    part=${rest%%/*}
    case $rest in */*) rest=${rest#*/} ;; *) rest="" ;; esac
    path=${path:+$path/}$part
    if [ ! -d "$ROOT/$path" ]; then
      mkdir "$ROOT/$path"
      record_dir "dir $path"
    fi
  done
}

files=""
put() {   # put SOURCE DEST: copy a file (mode 644, or 755 with -x)
  mode=644
  if [ "$1" = -x ]; then mode=755; shift; fi
  make_dir "$(dirname "$2")"
  cp "$1" "$ROOT/$2.tmp" && chmod "$mode" "$ROOT/$2.tmp"
  mv -f "$ROOT/$2.tmp" "$ROOT/$2"
  files="$files
file $2"
}

link() {  # link TARGET NAME: a symbolic link NAME -> TARGET (same directory)
  ln -sfn "$1" "$ROOT/$2"
  files="$files
file $2"
}

install_all() {
  VERSION=$1 MAJOR=$2
  [ -n "$VERSION" ] && [ -n "$MAJOR" ] || die "install: no version"
  # directories an earlier install created stay listed
  if [ -f "$ROOT/$MANIFEST" ]; then
    created_dirs=$(grep -E '^(dir|up) ' "$ROOT/$MANIFEST" || true)
  fi
  make_root
  put -x afv                bin/afv
  put    libafv.a           lib/libafv.a
  put -x libafv.so          "lib/libafv.so.$VERSION"
  link   "libafv.so.$VERSION" "lib/libafv.so.$MAJOR"
  link   "libafv.so.$MAJOR"   lib/libafv.so
  put    afv.h              include/afv.h
  put    afv_config.h       include/afv_config.h
  put    afv.pc             lib/pkgconfig/afv.pc
  put    doc/afv.1          share/man/man1/afv.1
  put    python/afv/__init__.py lib/python3/dist-packages/afv/__init__.py
  for doc in README.md CHANGELOG.md LICENSE CITATION.cff; do
    put "$doc" "share/doc/afv/$doc"
  done
  for example in examples/*; do
    put "$example" "share/doc/afv/$example"
  done
  make_dir "$(dirname "$MANIFEST")"
  { printf '# afv %s: what make install created under %s\n' "$VERSION" "$ROOT"
    printf '%s\n' "$created_dirs" "$files" "file $MANIFEST" | grep -v '^$'
  } > "$ROOT/$MANIFEST.tmp"
  mv -f "$ROOT/$MANIFEST.tmp" "$ROOT/$MANIFEST"
}

# ---- uninstall --------------------------------------------------------------
# "up K": the K-th parent of ROOT (its path as install saw it).
up_dir() {
  dir=$ROOT k=$1
  while [ "$k" -gt 0 ]; do dir=$(dirname "$dir"); k=$((k - 1)); done
  printf '%s\n' "$dir"
}

remove_dir() {
  if [ -d "$1" ] && ! rmdir "$1" 2>/dev/null; then
    echo "make uninstall: $1 kept (not empty: holds files afv did not install)"
  fi
}

uninstall_all() {
  if [ ! -f "$ROOT/$MANIFEST" ]; then
    echo "make uninstall: no $ROOT/$MANIFEST (nothing installed there by" \
         "make install of afv 0.2.0 or later): nothing removed" >&2
    exit 1
  fi
  list=$(grep -v '^#' "$ROOT/$MANIFEST")
  printf '%s\n' "$list" | while read -r kind path; do
    [ "$kind" = file ] && rm -f "$ROOT/$path"
  done
  # deepest first: dir lines by path length, longest first; then ROOT's
  # own ("up 0") and its parents' upwards
  printf '%s\n' "$list" | awk '$1 == "dir" { p = substr($0, 5); print length(p), p }' \
    | sort -rn | while read -r _ path; do remove_dir "$ROOT/$path"; done
  printf '%s\n' "$list" | awk '$1 == "up" { print $2 }' | sort -n \
    | while read -r k; do remove_dir "$(up_dir "$k")"; done
}

[ $# -ge 2 ] || die "usage: install ROOT VERSION MAJOR | uninstall ROOT"
ROOT=$2
case $1 in
  install)   install_all "${3:-}" "${4:-}" ;;
  uninstall) uninstall_all ;;
  *)         die "unknown mode $1" ;;
esac
