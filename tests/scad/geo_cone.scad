// A square pyramid: base 2 r^2 = 18, height 6, volume 36.
// expect volume: 36
// expect counts: vertices=5 faces=5
cylinder(h = 6, r1 = 3, r2 = 0, $fn = 4);
