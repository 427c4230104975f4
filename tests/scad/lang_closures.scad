// A function literal keeps the scope it was made in.
// expect echo: ECHO: 7, 13
function adder(n) = function(x) x + n;
add3 = adder(3);
add10 = adder(10);
echo(add3(4), add10(3));
