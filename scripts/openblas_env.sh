# Sourced by start.sh and test.sh. OpenBLAS 0.3.21 (Debian 12) does not recognise some virtual
# CPUs and falls back to generic SSE3 kernels (the BEM's dense LU runs 1.7x slower): name the
# kernel family the CPU supports, unless the user already chose one.
if [ -z "${OPENBLAS_CORETYPE:-}" ] && [ -r /proc/cpuinfo ]; then
  if grep -qw avx512f /proc/cpuinfo; then export OPENBLAS_CORETYPE=SkylakeX
  elif grep -qw avx2 /proc/cpuinfo; then export OPENBLAS_CORETYPE=Haswell
  fi
fi
