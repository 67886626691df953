# Sourced by check.sh and exit_check.sh. The tests that run the command
# (test_frontend_cli, test_frontend_gl_contexts, test_frontend_gl_compute)
# call it by the path the build compiled into them (BLURCULL_CLI:
# <build>/frontend/blurcull), which a bundle on the device lacks: it carries
# the executable (on PATH), not the build folder. link_compiled_cli EXE...
# links each such path that is missing to the bundle's blurcull; where the
# path exists (a run here) it does nothing.
link_compiled_cli() {
  local bundled exe cli
  bundled=$(command -v blurcull || true)
  [ -n "$bundled" ] || return 0
  for exe in "$@"; do
    [ -f "$exe" ] || continue
    cli=$(grep -a -o -m1 '/[[:graph:]]*/frontend/blurcull' "$exe" | head -1)
    [ -n "$cli" ] && [ ! -e "$cli" ] || continue
    mkdir -p "$(dirname "$cli")" && ln -s "$bundled" "$cli" && echo "linked $cli -> $bundled"
  done
}
