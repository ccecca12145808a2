# Sourced by the scripts here: sets $python to the interpreter src/cli/figures.h would pick
# ($VAEGAIL_PYTHON, else python3 on PATH, else /usr/bin/python3: the first that imports
# matplotlib), or to nothing.
python=
for candidate in ${VAEGAIL_PYTHON:-python3 /usr/bin/python3}; do
  if "$candidate" -c 'import matplotlib' 2> /dev/null; then python=$candidate; break; fi
done
