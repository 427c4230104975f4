// Recursive functions.
// expect echo: ECHO: 3.6288e+6, 6765
function fact(n) = n <= 1 ? 1 : n * fact(n - 1);
function fib(n) = n < 2 ? n : fib(n - 1) + fib(n - 2);
echo(fact(10), fib(20));
