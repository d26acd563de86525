# `cmake -DPROJECT_SOURCE_DIR=TREE -P cmake/CheckMethodTypes.cmake`: the configure-time check of
# cmake/MethodTypes.cmake on a tree (its test runs it on a tree with a clash).
include(${CMAKE_CURRENT_LIST_DIR}/MethodTypes.cmake)
msb_check_method_types()
