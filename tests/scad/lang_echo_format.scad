// echo's format: strings quoted, named arguments as name = value.
// expect echo: ECHO: "s", x = 5, [1, "a", true, undef]
// expect echo: ECHO: [0 : 2 : 5], inf, -inf
echo("s", x = 5, [1, "a", true, undef]);
echo([0:2:5], 1 / 0, -1 / 0);
