// polygon() with an outer path and a hole: 100 - 36.
// expect volume: 64
linear_extrude(1) polygon(points = [[0, 0], [10, 0], [10, 10], [0, 10], [2, 2], [8, 2], [8, 8], [2, 8]],
                          paths = [[0, 1, 2, 3], [4, 5, 6, 7]]);
