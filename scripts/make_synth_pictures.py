#!/usr/bin/env python3
"""Renders the pictures of docs/synth.md with `dlslam synth` (seed 1).

  scripts/make_synth_pictures.py [--dlslam build/bin/dlslam] [--out docs/img] [--work /tmp/synth_pictures]

synth_presets.png: frame 120 of every preset. synth_frames.png: colour, sensor
depth (0-4.5 m, black = no measurement) and mask (red person, yellow moving
person, blue movable object, cyan moving movable object, over the dimmed
colour) of walking_xyz frame 100 and sitting_static frame 90.
Needs python3 with numpy and OpenCV (Debian: python3-opencv).
"""
import argparse
import os
import subprocess

import cv2
import numpy as np

PRESETS = ["static", "walking_xyz", "walking_rpy", "walking_halfsphere", "walking_static", "sitting_static"]
TILE = (320, 240)


def frame_paths(folder, kind):
    with open(os.path.join(folder, kind + ".txt")) as f:
        rows = [line.split() for line in f if line.strip() and not line.startswith("#")]
    return [os.path.join(folder, row[1]) for row in rows]


def render(dlslam, work, preset, frames):
    out = os.path.join(work, preset)
    subprocess.run([dlslam, "synth", "--preset", preset, "--frames", str(frames), "--seed", "1", "--out", out],
                   check=True, stdout=subprocess.DEVNULL)
    return out


def tile(image):
    return cv2.resize(image, TILE, interpolation=cv2.INTER_AREA)


def label(image, text):
    for colour, thickness in (((0, 0, 0), 4), ((255, 255, 255), 1)):
        cv2.putText(image, text, (6, 22), cv2.FONT_HERSHEY_DUPLEX, 0.7, colour, thickness, cv2.LINE_AA)
    return image


def depth_picture(path):
    depth = cv2.imread(path, cv2.IMREAD_UNCHANGED).astype(np.float32) / 5000.0
    scaled = np.clip(depth / 4.5 * 255, 0, 255).astype(np.uint8)
    picture = cv2.applyColorMap(scaled, cv2.COLORMAP_TURBO)
    picture[depth == 0] = 0
    return picture


def mask_picture(mask_path, colour_path):
    mask = cv2.imread(mask_path, cv2.IMREAD_UNCHANGED)
    picture = cv2.imread(colour_path) // 3
    colours = {1: (0, 0, 230), 129: (0, 230, 255), 2: (230, 80, 0), 130: (255, 255, 0)}
    for value, bgr in colours.items():
        picture[mask == value] = bgr
    return picture


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--dlslam", default="build/bin/dlslam")
    parser.add_argument("--out", default="docs/img")
    parser.add_argument("--work", default="/tmp/synth_pictures")
    args = parser.parse_args()
    folders = {p: render(args.dlslam, args.work, p, 121) for p in PRESETS}
    tiles = [label(tile(cv2.imread(frame_paths(folders[p], "rgb")[120])), p) for p in PRESETS]
    grid = np.vstack([np.hstack(tiles[0:3]), np.hstack(tiles[3:6])])
    cv2.imwrite(os.path.join(args.out, "synth_presets.png"), grid, [cv2.IMWRITE_PNG_COMPRESSION, 9])

    rows = []
    for preset, index in (("walking_xyz", 100), ("sitting_static", 90)):
        folder = folders[preset]
        rgb = frame_paths(folder, "rgb")[index]
        depth = frame_paths(folder, "depth")[index]
        mask = frame_paths(folder, "mask")[index]
        rows.append(np.hstack([tile(cv2.imread(rgb)), tile(depth_picture(depth)),
                               cv2.resize(mask_picture(mask, rgb), TILE, interpolation=cv2.INTER_NEAREST)]))
    cv2.imwrite(os.path.join(args.out, "synth_frames.png"), np.vstack(rows), [cv2.IMWRITE_PNG_COMPRESSION, 9])


if __name__ == "__main__":
    main()
