// Everything subtracted: an empty result.
// expect volume: 0
// expect counts: faces=0
difference() { cube(1); cube(3, center = true); }
