namespace dlslam {}  // replaced by the evaluation code
