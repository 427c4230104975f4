// Endless non-tail recursion is an error, not a crash.
// expect error: recursion too deep
// expect no-openscad: an error (OpenSCAD: recursion detected)
function f(n) = 1 + f(n + 1);
echo(f(0));
