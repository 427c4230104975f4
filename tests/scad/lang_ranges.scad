// Ranges: the end is reached within a rounding step; negative steps count down.
// expect echo: ECHO: [0 : 1 : 3], [0, 0.25, 0.5, 0.75, 1], [5, 3, 1], 11, 4
echo([0:3], [for (i = [0:0.25:1]) i], [for (i = [5:-2:0]) i], len([for (i = [0:0.1:1]) i]),
     len([for (i = [0:0.1:0.3]) i]));
