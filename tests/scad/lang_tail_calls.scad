// A tail-recursive function 200000 calls deep: the sum 1 + ... + 200000.
// expect echo: ECHO: 2.00001e+10
function sum(n, acc = 0) = n == 0 ? acc : sum(n - 1, acc + n);
echo(sum(200000));
