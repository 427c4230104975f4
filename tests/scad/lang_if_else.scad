// if/else as statements choose geometry: only the 2 cube is made.
// expect echo: ECHO: "big"
// expect volume: 8
size = 2;
if (size > 1) { echo("big"); cube(size); } else { echo("small"); cube(1); }
