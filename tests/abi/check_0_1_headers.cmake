# tests/abi/rrc_0_1 must stay the 0.1 headers as published (git 766a8ff).
file(SHA256 ${DIR}/rrc.h h1)
file(SHA256 ${DIR}/rrc_vulkan.h h2)
if(NOT h1 STREQUAL "55b898bef528ba2bffb1cfa88e923f0329d0b92ed9956780a9c22caf8d214ab8" OR NOT h2 STREQUAL "13cb32fd85898d6cedc9295c2d2fdd215fbe47dc3ed5c6c1423e6d427609951b")
  message(FATAL_ERROR "tests/abi/rrc_0_1 differs from the 0.1 headers of git 766a8ff")
endif()
