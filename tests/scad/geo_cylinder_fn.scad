// A hexagonal prism: area (3 sqrt(3) / 2) r^2 times h.
// expect volume: 649.5190528383289
// expect counts: faces=8 vertices=12
cylinder(h = 10, r = 5, $fn = 6);
