// A square frustum: h / 3 (A1 + A2 + sqrt(A1 A2)) = 1 * (8 + 2 + 4).
// expect volume: 14
cylinder(h = 3, r1 = 2, r2 = 1, $fn = 4);
