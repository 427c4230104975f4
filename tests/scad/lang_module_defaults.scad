// Module parameters with defaults, positional and named.
// expect volume: 31.625
module box(s = 2, c = false) cube(s, center = c);
box();
box(3, c = true);
