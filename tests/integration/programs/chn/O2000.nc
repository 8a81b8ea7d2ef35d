O2000 (CT-CHN-01, channel 2; the spec's M99 here is taken as M30)
G00 X20 Z20
M98 P9020
M30
