"""Geometry and photometric augmentation with cv2.

All geometry is one affine map from output pixels to source-image pixels, applied with a single
cv2.warpAffine to the image (linear), the mask (nearest) and the teacher's stride-16 log-probabilities
(linear, through the teacher's own align_corners=True grid), so labels and soft targets stay aligned."""
import math

import cv2
import numpy as np

from . import IGNORE


def _h(m23):
    return np.vstack([m23, [0.0, 0.0, 1.0]])


def resize_map(src_hw, dst_hw):
    """cv2.resize / blobFromImage (half-pixel centres): dst pixel -> src pixel."""
    sy, sx = src_hw[0] / dst_hw[0], src_hw[1] / dst_hw[1]
    return np.array([[sx, 0, 0.5 * sx - 0.5], [0, sy, 0.5 * sy - 0.5], [0, 0, 1.0]])


def image_to_teacher_grid(image_hw, teacher_hw, grid_hw):
    """Source-image pixel -> cell of the teacher's stride-16 logit grid (upsampled with align_corners=True)."""
    to_input = np.linalg.inv(resize_map(image_hw, teacher_hw))       # image -> teacher input pixels
    gy = (grid_hw[0] - 1) / (teacher_hw[0] - 1)
    gx = (grid_hw[1] - 1) / (teacher_hw[1] - 1)
    return np.diag([gx, gy, 1.0]) @ to_input


def inference_map(image_hw, input_hw):
    """Output pixel -> image pixel for deployment: the whole image squashed to the network input."""
    return resize_map(image_hw, input_hw)


def random_map(rng, image_hw, input_hw, out_hw, scale=(0.5, 1.75), aspect=0.15, rotate_deg=8.0, anywhere=False):
    """Output (crop) pixel -> image pixel: the deployment view zoomed by a random scale and aspect,
    rotated a little, flipped half of the time and cropped at a random place (may reach past the border).
    A frame zoomed smaller than the crop sits in its centre, or with `anywhere` at a random place in it
    (pasted people)."""
    s = math.exp(rng.uniform(math.log(scale[0]), math.log(scale[1])))
    a = math.exp(rng.uniform(-aspect, aspect))
    frame_h, frame_w = input_hw[0] * s / a, input_hw[1] * s * a       # virtual frame size in output pixels
    frame_to_image = resize_map(image_hw, (frame_h, frame_w))

    def centre_range(frame, out):
        if anywhere:
            return min(out / 2, frame - out / 2), max(out / 2, frame - out / 2)
        return min(out / 2, frame / 2), max(frame - out / 2, frame / 2)
    # crop offset: the crop centre anywhere in the frame, so crops show borders sometimes
    cy = rng.uniform(*centre_range(frame_h, out_hw[0]))
    cx = rng.uniform(*centre_range(frame_w, out_hw[1]))
    ang = math.radians(rng.uniform(-rotate_deg, rotate_deg))
    c, sn = math.cos(ang), math.sin(ang)
    oy, ox = (out_hw[0] - 1) / 2, (out_hw[1] - 1) / 2
    flip = -1.0 if rng.random() < 0.5 else 1.0
    # output pixel -> centred -> flip -> rotate -> frame pixel
    centre = np.array([[1, 0, -ox], [0, 1, -oy], [0, 0, 1.0]])
    rot = np.array([[c * flip, -sn, cx - 0.5], [sn * flip, c, cy - 0.5], [0, 0, 1.0]])
    return frame_to_image @ rot @ centre


def warp(src, m33, out_hw, interp, border_value):
    return cv2.warpAffine(src, m33[:2], (out_hw[1], out_hw[0]), flags=interp | cv2.WARP_INVERSE_MAP,
                          borderMode=cv2.BORDER_CONSTANT, borderValue=border_value)


def warp_logp(logp, m33_grid, out_hw):
    """C x Gh x Gw log-probabilities -> C x h x w (C <= 4 for one warpAffine call)."""
    hwc = np.ascontiguousarray(logp.transpose(1, 2, 0))
    out = cv2.warpAffine(hwc, m33_grid[:2], (out_hw[1], out_hw[0]), flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP,
                         borderMode=cv2.BORDER_REPLICATE)
    return out.reshape(out_hw[0], out_hw[1], -1).transpose(2, 0, 1)


def photometric(rng, bgr, extended=False):
    """Brightness, contrast, saturation, hue jitter; sometimes blur or grayscale; `extended` adds motion blur
    and low light. uint8 in, uint8 out."""
    img = bgr.astype(np.float32)
    if rng.random() < 0.8:
        hsv = cv2.cvtColor(bgr, cv2.COLOR_BGR2HSV).astype(np.float32)
        hsv[..., 0] = (hsv[..., 0] + rng.uniform(-8, 8)) % 180
        hsv[..., 1] *= rng.uniform(0.65, 1.35)
        img = cv2.cvtColor(np.clip(hsv, 0, 255).astype(np.uint8), cv2.COLOR_HSV2BGR).astype(np.float32)
        img = (img - 128.0) * rng.uniform(0.7, 1.3) + 128.0 + rng.uniform(-35, 35)
    if rng.random() < 0.05:
        img[:] = cv2.cvtColor(np.clip(img, 0, 255).astype(np.uint8), cv2.COLOR_BGR2GRAY)[..., None]
    if rng.random() < 0.25:
        sigma = rng.uniform(0.4, 1.6)
        img = cv2.GaussianBlur(img, (0, 0), sigma)
    if extended and rng.random() < 0.15:   # motion blur: a handheld camera turning, people walking
        img = cv2.filter2D(img, -1, motion_kernel(rng.uniform(3, 11), rng.uniform(0, math.pi)))
    if extended and rng.random() < 0.15:   # low light: dark, contrast-poor, noisy (a dim lab, a corridor)
        img = 255.0 * (np.clip(img, 0, 255) / 255.0) ** rng.uniform(1.2, 2.2) * rng.uniform(0.35, 0.8)
        img += rng.normal(0, rng.uniform(3, 10), img.shape).astype(np.float32)
    if rng.random() < 0.2:
        img += rng.normal(0, rng.uniform(2, 8), img.shape).astype(np.float32)
    return np.clip(img, 0, 255).astype(np.uint8)


def motion_kernel(length, angle):
    """A normalised line kernel `length` px long at `angle` (radians)."""
    k = int(math.ceil(length)) | 1
    kernel = np.zeros((k, k), np.float32)
    c = (k - 1) / 2
    dx, dy = math.cos(angle) * (length - 1) / 2, math.sin(angle) * (length - 1) / 2
    cv2.line(kernel, (int(round(c - dx)), int(round(c - dy))), (int(round(c + dx)), int(round(c + dy))), 1.0, 1,
             cv2.LINE_AA)
    return kernel / kernel.sum()


def labels_from(person_mask, valid, logp, classes_n, teacher_person=False):
    """Hard labels: person from the ground-truth mask where there is one, other classes (chair) from the
    teacher's argmax elsewhere, IGNORE outside the source image. person_mask None = no people (negatives),
    unless teacher_person: then the teacher's people are the labels (real frames without masks)."""
    teacher = np.argmax(logp, axis=0).astype(np.uint8)
    # the teacher's movable classes; its person only where no mask says otherwise
    label = teacher.copy() if teacher_person else np.where(teacher >= 2, teacher, 0).astype(np.uint8)
    if person_mask is not None:
        label[person_mask] = 1
    label[~valid] = IGNORE
    assert classes_n >= 2
    return label
