// '#' highlights and keeps its subtree.
// expect volume: 8
#cube(2);
