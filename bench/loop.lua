-- bench: the twin of loop.kp in Lua 5.4 and LuaJIT (-joff); the registers are a table
local R = {}
for i = 0, 113 do R[i] = 0 end
R[1] = 0 R[2] = 0
repeat
  R[1] = R[1] + 1
  R[2] = R[2] / 2 + R[1]
until not (R[1] < 1000000)
print(R[1], R[2])
