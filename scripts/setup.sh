#!/usr/bin/env bash
# Install the Debian packages mocapdb needs. Idempotent: a no-op when all are present,
# and `apt-get update` runs only when something must be installed.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev
  libhdf5-dev hdf5-tools
  python3-h5py               # the README's h5py snippet, run by the store tests
  catch2
  libcli11-dev
  libzfp-dev zlib1g-dev      # compression baselines (zfp) and entropy coding (deflate)
  libzstd-dev                # the lossless tier of the clips; the packing module compares with it
  libssl-dev                 # SHA-256 of the imported source files (OpenSSL's libcrypto)
  nlohmann-json3-dev         # JSON: the schema mirror, --json output, the tests' JSON checks
  python3-zstandard          # the README's h5py snippet decodes a clip with it
  liblbfgspp-dev             # L-BFGS for the Gaussian-process hyperparameters
  liblapacke-dev libopenblas-dev  # LAPACK's divide-and-conquer eigensolver for large Gram matrices (OpenBLAS)
  pybind11-dev python3-dev   # the Python module (python/), built when found
  python3-numpy python3-pytest  # its arrays and its tests, run by ctest
  python3-torch              # mocapdb.torch, its tests and examples/training_windows.py's model
  python3-setuptools python3-pip python3-venv  # pip install --no-build-isolation ./python (README)
  clang libclang-rt-14-dev   # libFuzzer targets and the sanitizer build
  libtinygltf-dev            # glTF export (mocapdb export/synth -o OUT.gltf|.glb)
  libassimp-dev              # the glTF export's round-trip test reads it back with a second reader
  libcpp-httplib-dev libjs-three  # mocapdb serve: its HTTP server and the page's 3D (three.js)
  chromium chromium-driver python3-selenium  # the serve page's browser tests (CTest label browser)
  clang-format               # the style check of scripts/test.sh (.clang-format)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
