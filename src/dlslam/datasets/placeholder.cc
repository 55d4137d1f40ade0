namespace dlslam {}  // replaced when this module is built
