// sphere($fn = 4): two rings at 45 and 135 degrees: a 1 x 1 x sqrt(2) box.
// expect volume: 1.4142135623730951
// expect counts: vertices=8 faces=6
sphere(r = 1, $fn = 4);
