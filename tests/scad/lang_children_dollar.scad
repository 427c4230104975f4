// Children see the $ variables the module sets: the sphere has 4 segments.
// expect volume: 1.4142135623730951
module coarse() { $fn = 4; children(); }
coarse() sphere(1);
