# Model-discrepancy diagnosis (`jacobid diagnose`, included by host-tools/CMakeLists.txt).
