// Function literals as values: passed, returned, called directly.
// expect echo: ECHO: 9, 16, 2
f = function(x) x * x;
g = function(h, v) h(v);
echo(f(3), g(f, 4), (function(a) a + 1)(1));
