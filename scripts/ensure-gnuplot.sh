# Sourced by the report scripts: installs gnuplot (no X) when it is missing; only the
# reports with plots need it, so `make test` does not install it.
if ! command -v gnuplot > /dev/null; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends gnuplot-nox > /dev/null
fi
