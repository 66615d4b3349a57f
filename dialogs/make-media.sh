#!/usr/bin/env bash
# Generates every image and video of the example bundles in this folder with ffmpeg, from
# lavfi sources only (color, testsrc2, drawbox, drawtext, geq shapes, sine/aevalsrc audio):
# nothing is downloaded and no outside artwork is used. The generated files are checked in;
# this script documents how they were made and can remake them at any time.
#
#   bash dialogs/make-media.sh        (needs ffmpeg: apt-get update && apt-get install -y ffmpeg)
#
# Safe to run again: it overwrites its outputs, and with the same ffmpeg and fonts it writes
# byte-identical files (bitexact flags, single-threaded VP8). Text is drawn with the system's
# default sans-serif font (fc-match); without fontconfig or any font, images keep their shapes
# and lose their lettering. Videos are WebM (VP8 + Opus), except the paper's own Fig. 4 film,
# which is MPEG-1 as the paper has it (`docent serve` converts it for Chromium).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")"

for tool in ffmpeg ffprobe; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "make-media.sh: $tool not found; install it: apt-get update && apt-get install -y ffmpeg" >&2
        exit 1
    fi
done

TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# ---------------------------------------------------------------------------------------------
# Fonts: the default sans, bold and monospace faces, if fontconfig knows any font at all.
FONT="" FONT_BOLD="" FONT_MONO=""
FILTERS=$(ffmpeg -hide_banner -filters 2>/dev/null)   # (not piped into grep -q: SIGPIPE)
if command -v fc-match >/dev/null 2>&1 && [ -n "$(fc-list 2>/dev/null)" ] \
    && [[ $FILTERS == *" drawtext "* ]]; then
    FONT=$(fc-match -f '%{file}' sans)
    FONT_BOLD=$(fc-match -f '%{file}' 'sans:bold')
    FONT_MONO=$(fc-match -f '%{file}' monospace)
else
    echo "make-media.sh: no font for drawtext; drawing shapes only" >&2
fi

# ---------------------------------------------------------------------------------------------
# A tiny drawing vocabulary on top of one ffmpeg filter graph. `canvas` starts a picture, the
# other helpers append to it in drawing order, `save_png` renders it.
FG=""      # the filter graph being built
LAYER=0    # number of geq shape layers so far
TEXTS=0    # number of text files so far

canvas() { # canvas WIDTH HEIGHT COLOUR
    FG="color=c=$3:s=$1x$2:d=1,format=rgb24"
    LAYER=0
}

add() { FG+=",$1"; }

box() { # box X Y W H COLOUR  (filled rectangle)
    add "drawbox=x=$1:y=$2:w=$3:h=$4:color=$5:t=fill"
}

frame() { # frame X Y W H COLOUR THICKNESS  (rectangle outline)
    add "drawbox=x=$1:y=$2:w=$3:h=$4:color=$5:t=$6"
}

txt() { # txt X Y SIZE COLOUR TEXT [FONTFILE]  (text from a file: no escaping problems)
    [ -n "$FONT" ] || return 0
    TEXTS=$((TEXTS + 1))
    printf '%s' "$5" >"$TMP/text$TEXTS.txt"
    add "drawtext=fontfile=${6:-$FONT}:textfile=$TMP/text$TEXTS.txt:expansion=none:x=$1:y=$2:fontsize=$3:fontcolor=$4"
}

# shapes X Y W H SHAPE...  draws circles and ellipses (not possible with drawbox) as a geq
# layer of W x H pixels placed at X,Y. A SHAPE is "c CX CY R RRGGBB" or "e CX CY RX RY RRGGBB",
# in the layer's own coordinates; earlier shapes lie on top of later ones.
shapes() {
    local x=$1 y=$2 w=$3 h=$4
    shift 4
    local r=0 g=0 b=0 a=0 shape cond hex kind
    local -a s
    local i
    for ((i = $#; i >= 1; i--)); do
        shape=${!i}
        read -r -a s <<<"$shape"
        kind=${s[0]}
        if [ "$kind" = c ]; then
            cond="lt(hypot(X-${s[1]},Y-${s[2]}),${s[3]})"
            hex=${s[4]}
        else
            cond="lt(pow((X-${s[1]})/${s[3]},2)+pow((Y-${s[2]})/${s[4]},2),1)"
            hex=${s[5]}
        fi
        r="if($cond,$((16#${hex:0:2})),$r)"
        g="if($cond,$((16#${hex:2:2})),$g)"
        b="if($cond,$((16#${hex:4:2})),$b)"
        a="if($cond,255,$a)"
    done
    LAYER=$((LAYER + 1))
    FG+="[base$LAYER];color=c=black:s=${w}x${h}:d=1,format=rgba,geq=r='$r':g='$g':b='$b':a='$a'[shape$LAYER];[base$LAYER][shape$LAYER]overlay=x=$x:y=$y,format=rgb24"
}

save_png() { # save_png FILE [PIXEL_FORMAT]
    mkdir -p "$(dirname "$1")"
    ffmpeg -nostdin -v error -y -filter_complex "${FG}[out]" -map "[out]" -frames:v 1 -update 1 \
        -pix_fmt "${2:-rgb24}" -fflags +bitexact -flags +bitexact "$1"
    echo "wrote $1 ($(stat -c %s "$1") bytes)"
}

# save_webm FILE SECONDS AUDIO_SOURCE: renders the current graph (which must start from a
# video source lasting SECONDS) with the given lavfi audio source as VP8 + Opus.
save_webm() {
    mkdir -p "$(dirname "$1")"
    ffmpeg -nostdin -v error -y -filter_complex "${FG}[out]" -f lavfi -i "$3" \
        -map "[out]" -map 0:a -t "$2" -pix_fmt yuv420p \
        -c:v libvpx -b:v 300k -crf 12 -g 50 -threads 1 -c:a libopus -b:a 48k \
        -fflags +bitexact -flags:v +bitexact -flags:a +bitexact "$1"
    check_webm "$1" "$2"
}

# save_mpeg OUT SECONDS AUDIO: like save_webm, but MPEG-1 video and MPEG audio in an MPEG
# program stream (`.mpg`), the format of the paper's Fig. 4.
save_mpeg() {
    mkdir -p "$(dirname "$1")"
    ffmpeg -nostdin -v error -y -filter_complex "${FG}[out]" -f lavfi -i "$3" \
        -map "[out]" -map 0:a -t "$2" -pix_fmt yuv420p \
        -c:v mpeg1video -b:v 400k -g 25 -threads 1 -c:a mp2 -b:a 64k -f mpeg \
        -fflags +bitexact -flags:v +bitexact -flags:a +bitexact "$1"
    local codecs
    codecs=$(ffprobe -v error -show_entries stream=codec_name -of csv=p=0 "$1" | sort | tr '\n' ' ')
    if [ "$codecs" != "mp2 mpeg1video " ]; then
        echo "make-media.sh: $1 has codecs $codecs, want mpeg1video and mp2" >&2
        exit 1
    fi
    echo "wrote $1 ($(stat -c %s "$1") bytes, $codecs)"
}

# Verifies a video with ffprobe: VP8 or VP9 video, Opus audio, the expected duration.
check_webm() {
    local file=$1 want=$2 video audio duration
    video=$(ffprobe -v error -select_streams v:0 -show_entries stream=codec_name -of csv=p=0 "$file")
    audio=$(ffprobe -v error -select_streams a:0 -show_entries stream=codec_name -of csv=p=0 "$file")
    duration=$(ffprobe -v error -show_entries format=duration -of csv=p=0 "$file")
    case "$video/$audio" in
        vp8/opus | vp9/opus) ;;
        *) echo "make-media.sh: $file has codecs $video/$audio, want vp8 or vp9 with opus" >&2; exit 1 ;;
    esac
    if ! awk -v d="$duration" -v w="$want" 'BEGIN { exit !(d >= w - 0.1 && d <= w + 0.2) }'; then
        echo "make-media.sh: $file lasts $duration s, want $want s" >&2
        exit 1
    fi
    echo "wrote $file ($(stat -c %s "$file") bytes, $video/$audio, $duration s)"
}

# ---------------------------------------------------------------------------------------------
# paper-fig4: the exhibit video of Fig. 4, the paper's Exhibit/video.mpg, as MPEG-1.
paper_fig4() {
    FG="testsrc2=s=640x360:r=25:d=4,format=rgb24"
    box 0 250 640 110 0x000000@0.7
    txt 24 266 34 white "Exhibit video" "$FONT_BOLD"
    txt 24 312 22 white "Docent sample bundle, paper Fig. 4"
    save_mpeg paper-fig4/media/Exhibit/video.mpg 4 "sine=frequency=440:sample_rate=44100:duration=4,volume=0.2"
}

# ---------------------------------------------------------------------------------------------
# info-terminal: the floor plan of the (fictional) Harbour Science Museum.
info_terminal() {
    canvas 960 600 0xf4f1ea
    box 20 20 920 560 0x2c3e50
    room() { # room X Y W H COLOUR LABEL [WHAT]
        box "$1" "$2" "$3" "$4" "$5"
        txt "$1+18" "$2+16" 26 white "$6" "$FONT_BOLD"
        [ -z "${7:-}" ] || txt "$1+18" "$2+56" 20 white "$7"
    }
    room 26 26 334 368 0xc76d1e "Lighthouse Lab" "Build a lighthouse lamp"
    room 366 26 334 268 0x274060 "Planetarium" "Shows every hour"
    room 706 26 228 94 0x5d6d7e "Toilets"
    room 706 126 228 168 0x6e7f2a "Café" "Drinks and snacks"
    room 26 400 274 174 0x2f7d86 "Entrance & Shop"
    room 306 300 334 274 0x2a5f8f "Tide Hall" "Wave tank and tide clock"
    room 646 300 288 274 0x6a4f9a "Ship Models" "Ships of the harbour"
    box 110 574 100 6 0xf4f1ea                     # the main door
    txt 122 546 18 white "Main door"
    shapes 44 460 40 40 "c 20 20 14 e63946" "c 20 20 19 ffffff"
    txt 94 468 22 white "You are here" "$FONT_BOLD"
    save_png info-terminal/pages/images/map.png
}

# ---------------------------------------------------------------------------------------------
# museum-tour: hall map, a picture per exhibit, and the card punch video.

# Map coordinates (metres, y up) to map image pixels: 48 px per metre, drawn with a 20 px border
# that is cropped off at the end, so that the picture spans exactly the hall, x 0..20 m and
# y 0..12 m: `drive: bounds` in docent.yaml, by which the operator console places the robot on
# it (`operator: map`).
mx() { awk -v v="$1" 'BEGIN { printf "%d", 20 + 48 * v }'; }
my() { awk -v v="$1" 'BEGIN { printf "%d", 20 + 48 * (12 - v) }'; }

tour_map() {
    canvas 1000 616 0xd9d2c5
    box 20 20 960 576 0x3b3127                         # walls: the hall is 20 m x 12 m
    box 28 28 944 560 0xf4efe6                         # floor
    box 12 "$(my 7)" 20 96 0xf4efe6                    # entrance door, y = 5 m .. 7 m
    txt 40 "$(($(my 7) + 6))" 18 0x3b3127 "Entrance"
    plinth() { # plinth X0 Y0 X1 Y1 (metres) COLOUR LINE1 [LINE2]
        local px py w h
        px=$(mx "$1") py=$(my "$4")
        w=$(($(mx "$3") - px)) h=$(($(my "$2") - py))
        box "$px" "$py" "$w" "$h" "$5"
        txt "$px+10" "$py+10" 20 white "$6" "$FONT_BOLD"
        [ -z "${7:-}" ] || txt "$px+10" "$py+36" 20 white "$7" "$FONT_BOLD"
    }
    plinth 4 10 8 11.5 0x8c5a2b "1 Minicomputer"
    plinth 10 0.5 14 2 0x4f6b5b "2 Card punch"
    plinth 17 6 19.6 9 0x7a4e7e "3 Home" "computer"
    plinth 9 7 11 9 0xb7ab98 "Tape" "drives"        # other showcases, not on the tour
    plinth 15 10.5 18 11.5 0xb7ab98 "Terminals"
    # Robot stops (the acts' SET_WAYPOINT coordinates) as orange dots with a number.
    local stops=("S 2 6" "1 6 8.5" "2 12 3.5" "3 16 7.5")
    local stop name x y px py
    local -a dots=()
    for stop in "${stops[@]}"; do
        read -r name x y <<<"$stop"
        px=$(mx "$x") py=$(my "$y")
        dots+=("c $px $py 18 e07b39")
    done
    shapes 0 0 1000 616 "${dots[@]}"
    for stop in "${stops[@]}"; do
        read -r name x y <<<"$stop"
        px=$(mx "$x") py=$(my "$y")
        txt "$px-7" "$py-10" 22 white "$name" "$FONT_BOLD"
    done
    txt 140 "$(($(my 6) - 12))" 20 0x3b3127 "Start and finish"
    shapes 48 538 28 28 "c 14 14 12 e07b39"
    txt 84 540 20 0x3b3127 "Robot stops"
    box 720 560 240 8 0x3b3127                         # scale bar: 5 m = 240 px
    txt 812 532 20 0x3b3127 "5 m"
    add "crop=960:576:20:20"                            # the hall only: 960 x 576 px, 20 m x 12 m
    save_png museum-tour/pages/images/map.png
}

minicomputer_picture() {
    canvas 640 400 0xd9d2c5
    box 0 340 640 60 0x9c8f7a                          # floor
    # Processor cabinet with its blue front panel of lamps and toggle switches.
    box 56 36 248 308 0x3a3a3a
    box 60 40 240 300 0xe9e4d8
    box 76 70 208 104 0x1d3f8a
    local i x colour
    for ((i = 0; i < 16; i++)); do
        x=$((86 + i * 12))
        if (((i * 7 + 3) % 5 < 2)); then colour=0xff5a36; else colour=0x5a2a20; fi
        box "$x" 86 8 8 "$colour"
        if (((i / 3) % 2 == 0)); then colour=0xd94f2b; else colour=0xf0a830; fi
        box "$x" 118 8 28 "$colour"
    done
    txt 80 186 20 0x1d3f8a "MERIDIAN M-16" "$FONT_BOLD"
    for ((i = 0; i < 8; i++)); do box 80 $((226 + i * 12)) 200 4 0xb8b0a0; done
    # Tape drive cabinet with two reels behind a dark window.
    box 336 36 248 308 0x3a3a3a
    box 340 40 240 300 0xe9e4d8
    box 356 60 208 170 0x2b2b2b
    shapes 356 60 208 170 "c 52 82 12 2b2b2b" "c 52 82 44 9aa0a6" "c 156 82 12 2b2b2b" "c 156 82 44 9aa0a6"
    for ((i = 0; i < 4; i++)); do box $((372 + i * 48)) 256 32 20 0x5d6d7e; done
    box 372 296 176 24 0xb8b0a0
    save_png museum-tour/pages/images/minicomputer.png
}

card_punch_picture() {
    canvas 640 400 0xd9d2c5
    box 0 360 640 40 0x9c8f7a
    box 100 330 20 40 0x2f3a34                         # legs
    box 520 330 20 40 0x2f3a34
    box 80 170 480 170 0x6f8a7a                        # desk body
    box 60 150 520 28 0x5b7366                         # desk top
    box 400 70 130 80 0x4a5d52                         # card hopper
    box 410 56 110 20 0xefe2b8                         # cards waiting in the hopper
    box 130 196 240 76 0x2f3a34                        # keyboard
    local row col
    for ((row = 0; row < 4; row++)); do
        for ((col = 0; col < 10; col++)); do
            box $((140 + col * 22 + row * 4)) $((202 + row * 17)) 16 12 0xe9e4d8
        done
    done
    txt 410 200 24 white "KARTEX 80" "$FONT_BOLD"
    # A punched card lying on the desk: 20 columns, holes after a fixed pattern.
    box 150 96 200 54 0xefe2b8
    for ((col = 0; col < 20; col++)); do
        box $((156 + col * 9)) $((102 + (col * 5 % 7) * 6)) 5 5 0x3b3127
        box $((156 + col * 9)) $((102 + (col * 3 % 7 + 1) % 7 * 6)) 5 5 0x3b3127
    done
    save_png museum-tour/pages/images/card-punch.png
}

home_computer_picture() {
    canvas 640 400 0xd9d2c5
    box 0 346 640 54 0x8b6b4a                          # table
    box 150 30 320 250 0x3a3a3a                        # television set
    box 175 55 270 200 0x3048b8
    txt 190 72 18 white "LUMEN MICRO 48" "$FONT_MONO"
    txt 190 98 18 white "48K BASIC V1.2" "$FONT_MONO"
    txt 190 124 18 white "READY." "$FONT_MONO"
    box 190 150 12 18 white                            # cursor
    box 280 280 60 12 0x2b2b2b                         # TV stand
    box 110 292 400 54 0xd8cba8                        # the computer: a keyboard in a case
    local row col
    for ((row = 0; row < 3; row++)); do
        for ((col = 0; col < 14; col++)); do
            box $((126 + col * 26 + row * 6)) $((300 + row * 14)) 20 10 0x5a5045
        done
    done
    box 530 306 90 40 0x2e2e2e                         # cassette recorder for programs
    box 544 314 62 16 0x6b6b6b
    save_png museum-tour/pages/images/home-computer.png
}

# Card punch video: holes appear column by column while a sine "clack" sounds for each one.
card_punch_video() {
    FG="color=c=0x1e2a33:s=640x360:r=25:d=5,format=rgb24"
    txt 40 24 28 white "Kartex 80: punching a card" "$FONT_BOLD"
    box 60 80 520 210 0xefe2b8
    local col row t
    for ((row = 0; row < 6; row++)); do
        txt 70 $((96 + row * 30)) 16 0x9c8f7a "$row"
    done
    for ((col = 0; col < 20; col++)); do
        t=$(awk -v c="$col" 'BEGIN { printf "%.2f", 0.5 + 0.2 * c }')
        for row in $((col * 5 % 6)) $(((col * 2 + 3) % 6)); do
            add "drawbox=x=$((100 + col * 23)):y=$((94 + row * 30)):w=10:h=20:color=0x3b3127:t=fill:enable='gte(t,$t)'"
        done
    done
    txt 40 310 22 white "Each column of holes stands for one letter or digit."
    save_webm museum-tour/media/card-punch.webm 5 \
        "aevalsrc=0.4*sin(2*PI*660*t)*lt(mod(t-0.5\,0.2)\,0.04)*gte(t\,0.5)*lt(t\,4.5):s=48000:d=5"
}

# ---------------------------------------------------------------------------------------------
# poster-presenter: the poster and thumbnails for the pages (the acts light each section with
# HIGHLIGHT, so the projector needs no images).
# Poster: 848 x 1200 (A-series portrait). Title bar, then four sections in a 2 x 2 grid.
POSTER_W=848 POSTER_H=1200
TITLE_RECT="24 24 800 160"
SECTION_RECTS=("24 208 388 472" "436 208 388 472" "24 704 388 472" "436 704 388 472")

section() { # section N "X Y W H" HEADING LINE...
    local n=$1 x y w h
    read -r x y w h <<<"$2"
    local heading=$3
    shift 3
    box "$x" "$y" "$w" "$h" 0xfdfbf5
    box "$x" "$y" "$w" 64 0x1f6f8b
    box $((x + 12)) $((y + 8)) 48 48 0xf2b134
    txt $((x + 25)) $((y + 13)) 34 0x12355b "$n" "$FONT_BOLD"
    txt $((x + 74)) $((y + 20)) 23 white "$heading" "$FONT_BOLD"
    local i=0 line
    for line in "$@"; do
        txt $((x + 18)) $((y + 84 + i * 30)) 20 0x1d232b "$line"
        i=$((i + 1))
    done
}

poster() {
    canvas $POSTER_W $POSTER_H 0xdfe7ee
    local x y w h ix iy i k level
    read -r x y w h <<<"$TITLE_RECT"
    box "$x" "$y" "$w" "$h" 0x12355b
    txt $((x + 28)) $((y + 22)) 52 white "Tides in the Harbour" "$FONT_BOLD"
    txt $((x + 30)) $((y + 88)) 24 0xcfe3f0 "Why the sea rises and falls twice a day"
    txt $((x + 30)) $((y + 124)) 18 0xf2b134 "Harbour Science Museum" "$FONT_BOLD"

    section 1 "${SECTION_RECTS[0]}" "What is a tide?" \
        "Twice a day the sea rises" "and falls again. In our" "harbour the water climbs" \
        "about 3 metres from low" "tide to high tide."
    read -r x y w h <<<"${SECTION_RECTS[0]}"
    ix=$((x + 16)) iy=$((y + 252))
    box $ix $iy 356 204 0xe8f2f8
    box $ix $((iy + 30)) 90 174 0x8a8f96               # harbour wall
    box $((ix + 90)) $((iy + 150)) 266 54 0x1f5f8b     # water at low tide
    for ((i = 0; i < 11; i++)); do box $((ix + 96 + i * 24)) $((iy + 68)) 14 4 0x1f5f8b; done
    box $((ix + 112)) $((iy + 72)) 4 78 0x12355b       # the range between the two levels
    txt $((ix + 124)) $((iy + 98)) 20 0x12355b "3 m" "$FONT_BOLD"
    txt $((ix + 270)) $((iy + 40)) 18 0x12355b "HIGH" "$FONT_BOLD"
    txt $((ix + 270)) $((iy + 120)) 18 0x12355b "LOW" "$FONT_BOLD"

    section 2 "${SECTION_RECTS[1]}" "The Moon pulls the sea" \
        "The gravity of the Moon pulls" "the oceans into two bulges:" "one facing the Moon, one on" \
        "the far side. As Earth turns," "we pass through both each day."
    read -r x y w h <<<"${SECTION_RECTS[1]}"
    ix=$((x + 16)) iy=$((y + 252))
    box $ix $iy 356 204 0x0f2742
    shapes $ix $iy 356 204 "c 130 96 46 3f8f5a" "e 130 96 84 58 8cc8eb" "c 300 96 20 c8c8c8"
    txt $((ix + 104)) $((iy + 172)) 18 white "Earth"
    txt $((ix + 278)) $((iy + 132)) 18 white "Moon"

    section 3 "${SECTION_RECTS[2]}" "Spring and neap tides" \
        "When Sun, Earth and Moon line" "up, their pulls add up to the" "big spring tides. At half" \
        "moon they work against each" "other: the small neap tides."
    read -r x y w h <<<"${SECTION_RECTS[2]}"
    ix=$((x + 16)) iy=$((y + 252))
    box $ix $iy 356 204 0xe8f2f8
    txt $((ix + 10)) $((iy + 40)) 18 0x12355b "Spring" "$FONT_BOLD"
    txt $((ix + 10)) $((iy + 142)) 18 0x12355b "Neap" "$FONT_BOLD"
    for ((k = 0; k < 22; k++)); do
        level=$(awk -v k="$k" 'BEGIN { printf "%d", 48 + 40 * cos(2 * 3.14159265 * k / 11) }')
        box $((ix + 92 + k * 12)) $((iy + 96 - level)) 8 "$level" 0x1f6f8b
        level=$(awk -v k="$k" 'BEGIN { printf "%d", 48 + 16 * cos(2 * 3.14159265 * k / 11) }')
        box $((ix + 92 + k * 12)) $((iy + 196 - level)) 8 "$level" 0x6fa8c0
    done

    section 4 "${SECTION_RECTS[3]}" "Measuring our harbour" \
        "A tide gauge on the pier" "records the water level every" "hour. One day of readings" \
        "shows two highs and two lows," "about 12.4 hours apart."
    read -r x y w h <<<"${SECTION_RECTS[3]}"
    ix=$((x + 16)) iy=$((y + 252))
    box $ix $iy 356 204 0xe8f2f8
    for ((k = 0; k < 24; k++)); do
        level=$(awk -v k="$k" 'BEGIN { printf "%d", 84 + 66 * cos(2 * 3.14159265 * (k - 2) / 12.42) }')
        box $((ix + 22 + k * 13)) $((iy + 170 - level)) 10 "$level" 0x1f6f8b
    done
    box $((ix + 18)) $((iy + 170)) 320 3 0x12355b
    txt $((ix + 18)) $((iy + 178)) 16 0x12355b "0 h"
    txt $((ix + 160)) $((iy + 178)) 16 0x12355b "12 h"
    txt $((ix + 300)) $((iy + 178)) 16 0x12355b "24 h"
    save_png poster-presenter/media/poster.png
}

# Poster thumbnails for the pages: 3/8 of the size, the current section framed in orange.
thumbnail() { # thumbnail FILE ["X Y W H"]
    local chain="scale=318:450:flags=area" x y w h
    if [ -n "${2:-}" ]; then
        read -r x y w h <<<"$2"
        chain+=",drawbox=x=$((x * 3 / 8 - 4)):y=$((y * 3 / 8 - 4)):w=$((w * 3 / 8 + 8)):h=$((h * 3 / 8 + 8)):color=0xe4572e:t=6"
    fi
    mkdir -p "$(dirname "$1")"
    ffmpeg -nostdin -v error -y -i poster-presenter/media/poster.png -vf "$chain" -frames:v 1 -update 1 \
        -pix_fmt rgb24 -fflags +bitexact -flags +bitexact "$1"
    echo "wrote $1 ($(stat -c %s "$1") bytes)"
}

poster_presenter() {
    poster
    local n
    for n in 1 2 3 4; do
        thumbnail "poster-presenter/pages/images/poster-section-$n.png" "${SECTION_RECTS[n - 1]}"
    done
    thumbnail poster-presenter/pages/images/poster.png
}

paper_fig4
info_terminal
tour_map
minicomputer_picture
card_punch_picture
home_computer_picture
card_punch_video
poster_presenter
