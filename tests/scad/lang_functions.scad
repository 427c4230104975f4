// Functions with defaults, named arguments in any order.
// expect echo: ECHO: 6, 12, 10
function f(x, y = 2) = x * y;
echo(f(3), f(3, 4), f(y = 5, x = 2));
