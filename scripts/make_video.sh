#!/usr/bin/env bash
# Turns a demo's numbered PNG frames into an MP4 (H.264) or a GIF with ffmpeg.
# ffmpeg is not a patchspin dependency: install it yourself (Debian:
# apt-get install ffmpeg) to use this script.
#
# usage: scripts/make_video.sh FRAMES_DIR [OUT.mp4|OUT.gif] [--fps F] [--width W]
#   FRAMES_DIR  a demo's --out directory: frame_00000.png, frame_00001.png, ...
#   OUT         .mp4 (libx264, yuv420p, even width and height: plays everywhere)
#               or .gif (palettegen/paletteuse: one palette for the whole clip);
#               default FRAMES_DIR/<name of FRAMES_DIR>.mp4
#   --fps F     frame rate; default the demo's (summary.json "video"."fps"), else 30
#   --width W   scale to this width (height follows); default: the frames' own
#               width for MP4, at most 640 for GIF
# The GIF runs at min(F, 15) frames per second to stay small (frames dropped
# evenly, same duration).
#
# The ffmpeg commands it runs, for copying by hand (F = fps, D = frames dir):
#   ffmpeg -framerate F -i D/frame_%05d.png -c:v libx264 -pix_fmt yuv420p \
#          -vf "scale=trunc(iw/2)*2:trunc(ih/2)*2" -crf 18 -movflags +faststart out.mp4
#   ffmpeg -framerate F -i D/frame_%05d.png \
#          -vf "fps=15,scale=640:-1:flags=lanczos,split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=bayer:bayer_scale=5" out.gif
set -euo pipefail

usage() {
  echo "usage: $0 FRAMES_DIR [OUT.mp4|OUT.gif] [--fps F] [--width W]" >&2
  exit 2
}

dir=""
out=""
fps=""
width=""
while (($#)); do
  case "$1" in
    --fps) (($# >= 2)) || usage; fps=$2; shift 2 ;;
    --width) (($# >= 2)) || usage; width=$2; shift 2 ;;
    -h|--help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "$0: unknown option $1" >&2; usage ;;
    *)
      if [[ -z "$dir" ]]; then dir=$1
      elif [[ -z "$out" ]]; then out=$1
      else usage
      fi
      shift ;;
  esac
done
[[ -n "$dir" ]] || usage

if ! command -v ffmpeg >/dev/null 2>&1; then
  echo "$0: error: ffmpeg not found. It is not a patchspin dependency; install it to make videos" >&2
  echo "  (Debian/Ubuntu: apt-get install ffmpeg). The frames themselves are in $dir." >&2
  exit 1
fi
if [[ ! -d "$dir" ]]; then
  echo "$0: error: no directory $dir (run a demo with --out $dir first)" >&2
  exit 1
fi

# frames: frame_<digits>.png from 0 on, as render::FrameWriter numbers them
first=$(find "$dir" -maxdepth 1 -name 'frame_*.png' | LC_ALL=C sort | head -n 1)
if [[ -z "$first" ]]; then
  echo "$0: error: no frame_*.png in $dir" >&2
  exit 1
fi
stem=$(basename "$first" .png)
digits=${stem#frame_}
if [[ ! "$digits" =~ ^[0-9]+$ ]]; then
  echo "$0: error: cannot read the frame numbering of $first" >&2
  exit 1
fi
count=$(find "$dir" -maxdepth 1 -name 'frame_*.png' | wc -l)
start=$((10#$digits))
pattern="$dir/frame_%0${#digits}d.png"
last=$(printf "$pattern" $((start + count - 1)))
if [[ ! -f "$last" ]]; then
  echo "$0: error: the $count frames in $dir are not numbered contiguously from $start (no $last)" >&2
  exit 1
fi

# frame rate: --fps, else the demo's summary.json, else 30
if [[ -z "$fps" && -f "$dir/summary.json" ]] && command -v python3 >/dev/null 2>&1; then
  fps=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["video"]["fps"])' "$dir/summary.json" \
        2>/dev/null || true)
fi
fps=${fps:-30}
if ! awk -v f="$fps" 'BEGIN { exit !(f + 0 > 0) }'; then
  echo "$0: error: --fps must be a positive number: got '$fps'" >&2
  exit 2
fi
if [[ -n "$width" && ! "$width" =~ ^[0-9]+$ ]]; then
  echo "$0: error: --width must be a whole number of pixels: got '$width'" >&2
  exit 2
fi

if [[ -z "$out" ]]; then
  out="$dir/$(basename "$(cd "$dir" && pwd)").mp4"
fi
case "$out" in
  *.mp4)
    # (the list in a variable first: grep -q closing the pipe early would fail
    # the pipeline under pipefail)
    encoders=$(ffmpeg -hide_banner -encoders 2>/dev/null || true)
    if [[ "$encoders" != *libx264* ]]; then
      echo "$0: error: this ffmpeg has no libx264 encoder (Debian's ffmpeg has it)" >&2
      exit 1
    fi
    # even width and height: yuv420p halves the chroma resolution
    if [[ -n "$width" ]]; then
      scale="scale=trunc(${width}/2)*2:-2:flags=lanczos"
    else
      scale="scale=trunc(iw/2)*2:trunc(ih/2)*2"
    fi
    ffmpeg -hide_banner -loglevel error -y -framerate "$fps" -start_number "$start" -i "$pattern" \
      -vf "$scale" -c:v libx264 -pix_fmt yuv420p -crf 18 -preset medium -movflags +faststart "$out"
    ;;
  *.gif)
    gfps=$(awk -v f="$fps" 'BEGIN { print (f > 15 ? 15 : f) }')
    gwidth=${width:-"min(iw\,640)"}
    ffmpeg -hide_banner -loglevel error -y -framerate "$fps" -start_number "$start" -i "$pattern" \
      -vf "fps=${gfps},scale=${gwidth}:-1:flags=lanczos,split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=bayer:bayer_scale=5" \
      -loop 0 "$out"
    ;;
  *)
    echo "$0: error: the output must end in .mp4 or .gif: got $out" >&2
    exit 2
    ;;
esac
seconds=$(awk -v n="$count" -v f="$fps" 'BEGIN { printf "%.2f", n / f }')
case "$out" in
  *.gif) echo "$out: $count frames at $fps fps ($seconds s), written at $gfps fps" ;;
  *) echo "$out: $count frames at $fps fps ($seconds s)" ;;
esac
