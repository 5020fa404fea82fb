# The real readers the integration tests check moyo's output with, the
# way CI installs them:
#   - vpype reads our SVG, pygcode our G-code, ezdxf our DXF and trimesh
#     our OBJ (as Blender does): a Python virtual environment with pinned
#     versions,
#     target/vpype-venv (MOYO_VPYPE, MOYO_PYTHON);
#   - hp2xx draws our HPGL: Debian's package, unpacked into target/hp2xx
#     without installing it (MOYO_HP2XX);
#   - Chromium runs the studio's page: Debian's chromium and
#     chromium-driver packages (MOYO_CHROMIUM, MOYO_CHROMEDRIVER); this
#     one needs root (apt-get install).
#
# Use, from the repository's top folder:
#   source tools/test-env.sh && cargo test --locked
# What is already there is kept (a second run installs nothing). A reader
# that cannot be installed is named and its variables are left unset, so
# its tests skip and `cargo test` lists them at its end; with CI set
# (.ci/run) it is a failure instead.

moyo_test_env() {
  local venv=target/vpype-venv failed=""
  local pip=("$venv/bin/pip" install --quiet --disable-pip-version-check)
  if [ ! -x "$venv/bin/vpype" ]; then
    python3 -m venv "$venv" && "${pip[@]}" "vpype==1.15.0"
  fi
  if [ -x "$venv/bin/python" ]; then
    "$venv/bin/python" -c 'import pygcode' 2>/dev/null || "${pip[@]}" "pygcode==0.2.1"
    "$venv/bin/python" -c 'import ezdxf' 2>/dev/null || "${pip[@]}" "ezdxf==1.4.4"
    "$venv/bin/python" -c 'import trimesh' 2>/dev/null || "${pip[@]}" "trimesh==5.2.0" "numpy==2.4.6"
  fi
  if [ -x "$venv/bin/vpype" ] && "$venv/bin/python" -c 'import pygcode, ezdxf, trimesh' 2>/dev/null; then
    export MOYO_VPYPE="$PWD/$venv/bin/vpype" MOYO_PYTHON="$PWD/$venv/bin/python"
  else
    failed="$failed vpype/pygcode/ezdxf/trimesh (python3 -m venv, pip)"
  fi

  local hp2xx_root=target/hp2xx
  local hp2xx="$hp2xx_root/usr/bin/hp2xx"
  if [ ! -x "$hp2xx" ]; then
    rm -rf "$hp2xx_root"
    mkdir -p "$hp2xx_root/deb"
    # apt-get download needs package lists; a fresh machine may have none
    # (refreshing them needs root, which CI has).
    (cd "$hp2xx_root/deb" && apt-get download -q hp2xx) ||
      { apt-get update -q && (cd "$hp2xx_root/deb" && apt-get download -q hp2xx); }
    dpkg -x "$hp2xx_root"/deb/hp2xx_*.deb "$hp2xx_root" 2>/dev/null || true
  fi
  # Its shared libraries (libX11, libpng, libtiff, libjpeg) come with the
  # machine; say so plainly if one is missing.
  local missing
  if [ -x "$hp2xx" ] && missing=$(ldd "$hp2xx" | grep 'not found'); then
    printf 'hp2xx lacks shared libraries:\n%s\n' "$missing" >&2
    failed="$failed hp2xx (its libraries)"
  elif [ -x "$hp2xx" ]; then
    export MOYO_HP2XX="$PWD/$hp2xx"
  else
    failed="$failed hp2xx (apt-get download hp2xx)"
  fi

  # The studio's browser tests (tests/studio_browser.rs): packages with
  # their libraries, so root is needed (CI runs as root).
  if [ ! -x /usr/bin/chromedriver ] || [ ! -x /usr/bin/chromium ]; then
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium chromium-driver ||
      { apt-get update -q &&
        DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium chromium-driver; }
  fi
  if [ -x /usr/bin/chromedriver ] && [ -x /usr/bin/chromium ]; then
    export MOYO_CHROMEDRIVER=/usr/bin/chromedriver MOYO_CHROMIUM=/usr/bin/chromium
  else
    failed="$failed chromium (as root: apt-get install chromium chromium-driver)"
  fi

  if [ -n "$failed" ]; then
    printf 'tools/test-env.sh: not installed:%s\n' "$failed" >&2
    [ -z "${CI:-}" ]
  else
    echo "tools/test-env.sh: vpype, pygcode, ezdxf, trimesh, hp2xx and Chromium are ready; cargo test --locked runs every test" >&2
  fi
}
moyo_test_env
