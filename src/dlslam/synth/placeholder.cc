namespace dlslam {}  // replaced by the renderer
