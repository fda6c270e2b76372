; a probe camera that sees only noise (see e-teeth.kp)
teeth    = 2
diameter = 20000
noise    = 1
blur     = 3
image    = 512
seed     = 1
