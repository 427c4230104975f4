// A frustum from a 2-square to a 1-square, 3 high: 4 + 1 + 2.
// expect volume: 7
linear_extrude(height = 3, scale = 0.5) square(2, center = true);
