#!/usr/bin/python3
"""Images side by side with a caption over each: figures like seed 001's Figs. 5.3.2.B and 5.3.3.A
from `shadowlab render` outputs (docs/coloured-shadows.md shows the commands).

    tools/strip.py --out strip.png a.png "translucent shadows" b.png "CSSM2 9x9" ...
"""
import argparse
import sys

from PIL import Image, ImageDraw, ImageFont

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"   # fonts-dejavu-core (tools/setup.sh)


def strip(pairs, out, caption_height=28):
    images = [(Image.open(path).convert("RGB"), label) for path, label in pairs]
    height = max(image.height for image, _ in images)
    width = sum(image.width for image, _ in images)
    canvas = Image.new("RGB", (width, height + caption_height), (24, 24, 24))
    draw = ImageDraw.Draw(canvas)
    try:
        font = ImageFont.truetype(FONT, int(caption_height * 0.6))
    except OSError:
        font = ImageFont.load_default()
    x = 0
    for image, label in images:
        canvas.paste(image, (x, caption_height))
        draw.text((x + 8, caption_height * 0.15), label, fill=(235, 235, 235), font=font)
        x += image.width
    canvas.save(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True, help="PNG to write")
    parser.add_argument("items", nargs="+", help="image, caption, image, caption, ...")
    args = parser.parse_args(argv)
    if len(args.items) % 2:
        parser.error("expected pairs of image and caption")
    pairs = list(zip(args.items[0::2], args.items[1::2]))
    try:
        strip(pairs, args.out)
    except (OSError, ValueError) as e:
        print(f"strip.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
