#!/usr/bin/env bash
# The shared probe set on this machine: makes it (probe_set make, about a minute) into PROBE_SET
# (default ~/.cache/hideseek/probe_set) when it is missing, checks it against the committed
# definition (docs/probe_set/labels.csv and images.sha256: the same images on every machine), and
# probes the baselines (five random-init networks and the pixels) into docs/probe_set/baselines.csv,
# and their t-SNE neighbourhood scores into docs/probe_set/tsne_baselines.csv, when those are
# missing. Prints the probe set's folder.
# usage: src/hideseek_analysis/scripts/probe_set.sh [--fix]   --fix (re)writes docs/probe_set/ from a new probe set: the
#        probe set is fixed once, before any sweep run is analysed; do not move it after.
set -euo pipefail
cd "$(dirname "$(realpath "$0")")/../../.."
source scripts/env.sh
dir=$(realpath -m "${PROBE_SET:-$HOME/.cache/hideseek/probe_set}")
docs=docs/probe_set
fix=${1:-}
bin=devel/lib/hideseek_analysis/probe_set
# One maker at a time: two runs finishing together must not write or read a half-made set.
mkdir -p "$(dirname "$dir")"
exec 9> "$dir.lock"
flock 9
if [ ! -s "$dir/images.npy" ] || [ ! -s "$dir/labels.csv" ]; then
  echo "probe_set.sh: making the probe set in $dir" >&2
  "$bin" make "$dir" --game v2 >&2  # the committed set was drawn from game v2, whichever game is the default
fi
sha=$(sha256sum "$dir/images.npy" | cut -d' ' -f1)
if [ "$fix" = --fix ]; then
  mkdir -p "$docs"
  cp "$dir/labels.csv" "$dir/composition.md" "$docs/"
  echo "$sha  images.npy" > "$docs/images.sha256"
  rm -f "$docs/baselines.csv" "$docs/tsne_baselines.csv" "$docs/tsne_random_init_0.csv"
  echo "probe_set.sh: the probe set is fixed in $docs (images.npy $sha)" >&2
elif [ -s "$docs/labels.csv" ]; then
  cmp -s "$dir/labels.csv" "$docs/labels.csv" || { echo "probe_set.sh: $dir/labels.csv differs from the committed $docs/labels.csv: remove $dir to make it again" >&2; exit 1; }
  [ "$sha" = "$(cut -d' ' -f1 "$docs/images.sha256")" ] || { echo "probe_set.sh: $dir/images.npy ($sha) is not the committed probe set's images ($docs/images.sha256)" >&2; exit 1; }
else
  echo "probe_set.sh: no committed probe set in $docs: fix one first (src/hideseek_analysis/scripts/probe_set.sh --fix)" >&2
  exit 1
fi
random_init() {
  for s in 0 1 2 3 4; do
    [ -s "$dir/random_init_$s.npy" ] || "$bin" features "$dir" "$dir/random_init_$s.npy" --random-init "$s" >&2
  done
}
if [ ! -s "$docs/baselines.csv" ]; then
  echo "probe_set.sh: probing the baselines (5 random-init networks, pixels)" >&2
  random_init
  /usr/bin/python3 src/hideseek_analysis/scripts/probes.py baselines "$dir" "$dir" "$docs/baselines.csv" >&2
fi
if [ ! -s "$docs/tsne_baselines.csv" ]; then
  echo "probe_set.sh: the t-SNE of the baselines (5 random-init networks, pixels)" >&2
  random_init
  /usr/bin/python3 src/hideseek_analysis/scripts/probes.py tsne-baselines "$dir" "$dir" "$docs/tsne_baselines.csv" >&2
fi
echo "$dir"
