-- bench: the twin of trig.kp in Lua 5.4 and LuaJIT (-joff) (angles in 0.001 degree)
local R = {}
for i = 0, 113 do R[i] = 0 end
local deg = math.pi / 180000
local sin, cos, asin = math.sin, math.cos, math.asin
repeat
  R[1] = R[1] + 1
  R[2] = sin(R[1] * deg) + cos(R[1] * deg)
  R[3] = asin(R[2] / 2) / deg
until not (R[1] < 1000000)
print(R[1], R[2], R[3])
