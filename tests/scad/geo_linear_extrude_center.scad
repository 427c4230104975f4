// A 4-gon of circumradius 1 (area 2), 4 high, centred.
// expect volume: 8
// expect bbox: [-1, -1, -2] [1, 1, 2]
linear_extrude(height = 4, center = true) circle(1, $fn = 4);
