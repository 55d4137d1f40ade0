"""Training data: split lists, the teacher's cached logits, augmentation and the torch Dataset."""
import json
import os

TRAINING_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REPO_DIR = os.path.dirname(TRAINING_DIR)
SHARED_DATA = os.environ.get('DLSLAM_SHARED_DATA', os.path.join(REPO_DIR, '..', 'shared', 'data'))
CACHE_DIR = os.path.join(TRAINING_DIR, 'data', 'teacher_cache')
CLASSES_JSON = os.path.join(TRAINING_DIR, 'config', 'classes.json')
TEACHER_DIR = os.path.join(SHARED_DATA, 'models', 'deeplabv3-mnv2-voc')
IGNORE = 255


def load_classes(path=CLASSES_JSON):
    with open(path) as f:
        classes = json.load(f)['classes']
    if [c['id'] for c in classes] != list(range(len(classes))):
        raise ValueError(f'{path}: class ids must be 0..N-1 in order')
    return classes
