%
O0002 (a long slow cut: used to stop a machine while it moves)
N10 G01 Z-200. F300
N20 M30
%
