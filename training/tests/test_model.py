#!/usr/bin/env python3
"""Model tests: ReLU6 export form, ASPP structure and size, output shapes, OpenCV-loadable ONNX equal to PyTorch.

  /usr/bin/python3 training/tests/test_model.py"""
import os
import sys
import tempfile
import unittest

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from model import build_model, export_friendly  # noqa: E402
from model.aspp import FactorizedAtrousBranch, ImprovedASPP, OriginalASPP  # noqa: E402
from model.layers import ReLU6, count_parameters  # noqa: E402


class ReLU6Test(unittest.TestCase):
    def test_export_form_equals_nn_relu6(self):
        x = torch.linspace(-20, 20, 100001)
        ref = torch.nn.ReLU6()(x)
        with export_friendly():
            self.assertTrue(torch.equal(ReLU6()(x), ref))
        self.assertTrue(torch.equal(ReLU6()(x), ref))


class ASPPTest(unittest.TestCase):
    def test_improved_has_six_maps_with_paper_rates(self):
        head = ImprovedASPP(320, 256)
        rates = [b.dw_3x1.dilation[0] for b in head.branches if isinstance(b, FactorizedAtrousBranch)]
        self.assertEqual(rates, [4, 8, 12, 16])
        self.assertEqual(head.project[0].in_channels, 6 * 256)
        b = head.branches[1]
        self.assertEqual(b.dw_3x1.kernel_size, (3, 1))
        self.assertEqual(b.dw_1x3.kernel_size, (1, 3))
        self.assertEqual(b.dw_1x3.dilation, (1, 4))
        self.assertEqual(b.dw_3x1.groups, 320)

    def test_improved_is_much_smaller_than_original(self):
        # independent count of the original head: 1x1 + 3 full 3x3 + pooling conv + projection of 5 maps
        c_in, c = 320, 256
        original = (c_in * c + 2 * c) + 3 * (9 * c_in * c + 2 * c) + (c_in * c + c) + (5 * c * c + 2 * c)
        self.assertEqual(count_parameters(OriginalASPP(c_in, c)), original)
        self.assertLess(count_parameters(ImprovedASPP(c_in, c)), 0.67 * original)

    def test_same_spatial_size(self):
        x = torch.randn(2, 64, 9, 11)
        for head in (ImprovedASPP(64, 32), OriginalASPP(64, 32)):
            self.assertEqual(tuple(head.eval()(x).shape), (2, 32, 9, 11))


class ModelTest(unittest.TestCase):
    def test_output_shape_all_presets(self):
        for preset in ('mnv2_w05', 'mnv2_w10', 'resnest26_w05'):
            m = build_model(preset, num_classes=3).eval()
            with torch.no_grad():
                self.assertEqual(tuple(m(torch.zeros(1, 3, 65, 97)).shape), (1, 3, 65, 97), preset)

    def test_onnx_in_opencv_equals_pytorch(self):
        import cv2
        from export_onnx import export
        for preset in ('mnv2_w05', 'resnest26_w05'):
            torch.manual_seed(0)
            m = build_model(preset, num_classes=3).eval()
            for bn in (x for x in m.modules() if isinstance(x, torch.nn.BatchNorm2d)):   # non-trivial BN
                bn.running_mean.uniform_(-0.1, 0.1)
                bn.running_var.uniform_(0.5, 1.5)
            x = torch.rand(1, 3, 129, 161) * 2 - 1
            with torch.no_grad():
                ref = m(x).numpy()
            with tempfile.TemporaryDirectory() as tmp:
                path = os.path.join(tmp, 'm.onnx')
                export(m, path, 129, 161)
                net = cv2.dnn.readNetFromONNX(path)
                net.setInput(x.numpy())
                out = net.forward()
            self.assertEqual(out.shape, ref.shape)
            diff = float(np.abs(out - ref).max())
            print(f'{preset}: cv2.dnn vs PyTorch max |diff| {diff:.2e} (logit range {np.abs(ref).max():.2f})')
            self.assertLess(diff, 1e-3)

    def test_relu6_fused_for_opencv_gives_the_portable_exports_logits(self):
        import cv2
        import onnx
        from export_onnx import export
        torch.manual_seed(1)
        m = build_model('mnv2_w05', num_classes=3).eval()
        x = (torch.rand(1, 3, 65, 81) * 2 - 1).numpy()
        outs = {}
        with tempfile.TemporaryDirectory() as tmp:
            for portable in (False, True):
                path = os.path.join(tmp, f'm{portable}.onnx')
                export(m, path, 65, 81, portable=portable)
                ops = [n.op_type for n in onnx.load(path).graph.node]
                self.assertEqual('Clip' in ops, not portable)
                self.assertEqual('Sub' in ops, portable)
                net = cv2.dnn.readNetFromONNX(path)
                net.setInput(x)
                outs[portable] = net.forward()
        self.assertLess(float(np.abs(outs[False] - outs[True]).max()), 1e-5)


    def test_dilated_depthwise_rewritten_onto_opencvs_fast_kernel(self):
        """The ASPP's 3x1+1x3 pairs become one 3x3 and every dilated depthwise 3x3 takes its padding from
        a Pad node (the form OpenCV 4.6 runs 5-6x faster), with PyTorch's logits. 273 wide, so the
        stride-16 map (18 wide) is wide enough for that kernel, and its left border is where a padded
        dilated convolution would read the wrong column."""
        import cv2
        import onnx
        from onnx import helper
        from export_onnx import export
        torch.manual_seed(2)
        m = build_model('mnv2_w05', num_classes=3).eval()
        x = torch.rand(1, 3, 65, 273) * 2 - 1
        with torch.no_grad():
            ref = m(x).numpy()
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, 'm.onnx')
            export(m, path, 65, 273)
            graph = onnx.load(path).graph
            convs = [{a.name: helper.get_attribute_value(a) for a in n.attribute}
                     for n in graph.node if n.op_type == 'Conv']
            dilated = [c for c in convs if max(c.get('dilations', [1, 1])) > 1]
            self.assertEqual(len(dilated), 3 + 4)   # the last backbone stage's three, one per ASPP branch
            self.assertTrue(all(list(c['pads']) == [0, 0, 0, 0] for c in dilated))
            self.assertFalse(any(list(c['kernel_shape']) in ([3, 1], [1, 3]) for c in convs))
            self.assertEqual(sum(n.op_type == 'Pad' for n in graph.node), 7)
            net = cv2.dnn.readNetFromONNX(path)
            net.setInput(x.numpy())
            out = net.forward()
        diff = float(np.abs(out - ref).max())
        print(f'rewritten depthwise: cv2.dnn vs PyTorch max |diff| {diff:.2e}')
        self.assertLess(diff, 1e-4)


class SequenceEvalTest(unittest.TestCase):
    """evaluate.py --sequence: person IoU against a sequence's mask.txt, frames matched by timestamp."""

    def test_iou_of_a_known_prediction(self):
        import cv2
        from evaluate import run_sequence_eval
        with tempfile.TemporaryDirectory() as d:
            os.makedirs(os.path.join(d, 'rgb'))
            os.makedirs(os.path.join(d, 'mask'))
            for i in range(2):
                cv2.imwrite(os.path.join(d, 'rgb', f'{i}.png'), np.full((40, 40, 3), 90, np.uint8))
                mask = np.zeros((40, 40), np.uint8)
                mask[:, :10] = 129   # the left quarter is a person
                cv2.imwrite(os.path.join(d, 'mask', f'{i}.png'), mask)
            with open(os.path.join(d, 'rgb.txt'), 'w') as f:
                f.write('# colour\n0.0 rgb/0.png\n0.033333 rgb/1.png\n')
            with open(os.path.join(d, 'mask.txt'), 'w') as f:
                f.write('0.0 mask/0.png\n0.033333 mask/1.png\n')

            def left_half(x):   # person on the left half of the network input
                label = np.zeros(x.shape[2:], np.int64)
                label[:, :x.shape[3] // 2] = 1
                return label
            s = run_sequence_eval(left_half, d, (17, 17), every=1)
            self.assertEqual(s['frames'], 2)
            self.assertAlmostEqual(s['person_iou_pooled'], 0.5, delta=0.03)
            self.assertAlmostEqual(s['person_iou_mean'], 0.5, delta=0.03)
            self.assertAlmostEqual(s['false_positive_share'], 0.25, delta=0.03)
            with open(os.path.join(d, 'mask.txt'), 'a') as f:
                f.write('0.066666\n')
            with self.assertRaises(SystemExit) as e:
                run_sequence_eval(left_half, d, (17, 17), every=1)
            self.assertIn('mask.txt', str(e.exception))
            self.assertIn('mask.txt:3:', str(e.exception))   # file and line
            with open(os.path.join(d, 'mask.txt'), 'w') as f:
                f.write('5.0 mask/0.png\n')                  # no timestamp in common
            with self.assertRaises(SystemExit) as e:
                run_sequence_eval(left_half, d, (17, 17), every=1)
            self.assertIn('no frame', str(e.exception))
            os.remove(os.path.join(d, 'mask.txt'))
            with self.assertRaises(SystemExit) as e:
                run_sequence_eval(left_half, d, (17, 17), every=1)
            self.assertIn('mask.txt: cannot read', str(e.exception))


if __name__ == '__main__':
    unittest.main()
