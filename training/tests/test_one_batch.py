#!/usr/bin/env python3
"""CI smoke test: one tiny training step, checkpoint, exact resume. Exit code 0 = pass.

  /usr/bin/python3 training/tests/test_one_batch.py
Uses the shared data + teacher cache when present, random tensors otherwise."""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import train  # noqa: E402


class OneBatchTest(unittest.TestCase):
    def test_one_batch_and_resume(self):
        train.one_batch(['--init', 'none'])   # no pretrained weights needed


if __name__ == '__main__':
    unittest.main()
