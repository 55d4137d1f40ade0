#!/usr/bin/env python3
"""Runs a training test when PyTorch and ONNX are installed, else exits 77 (ctest: skipped).

The SLAM needs no PyTorch: `scripts/setup.sh --training` installs it (CI does).
  /usr/bin/python3 training/tests/run_if_available.py training/tests/test_model.py"""
import importlib.util
import runpy
import sys

missing = [m for m in ("torch", "onnx", "numpy", "cv2") if importlib.util.find_spec(m) is None]
if missing:
    print(f"skipped: {', '.join(missing)} not installed; run scripts/setup.sh --training", file=sys.stderr)
    sys.exit(77)
script = sys.argv[1]
sys.argv = sys.argv[1:]
runpy.run_path(script, run_name="__main__")
