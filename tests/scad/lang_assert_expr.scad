// assert() in an expression passes through to its body.
// expect echo: ECHO: 2
function root(x) = assert(x >= 0, "negative") sqrt(x);
echo(root(4));
