# Every dependency is a Debian package found here; nothing is downloaded at build time.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(GeographicLib REQUIRED)          # /usr/share/cmake/geographiclib/FindGeographicLib.cmake
find_package(pugixml REQUIRED)
find_package(spdlog REQUIRED)
find_package(fmt REQUIRED)  # formatting in eval/ reports (spdlog depends on it too)
find_package(CLI11 REQUIRED)
find_package(Threads REQUIRED)

# nanoflann 1.4 (Debian) is a single header without a CMake package.
find_path(NANOFLANN_INCLUDE_DIR nanoflann.hpp REQUIRED)
add_library(nanoflann_headers INTERFACE)
target_include_directories(nanoflann_headers SYSTEM INTERFACE ${NANOFLANN_INCLUDE_DIR})

# libpcap ships no CMake package on Debian.
find_path(PCAP_INCLUDE_DIR pcap/pcap.h REQUIRED)
find_library(PCAP_LIBRARY pcap REQUIRED)
add_library(pcap_lib INTERFACE)
target_include_directories(pcap_lib SYSTEM INTERFACE ${PCAP_INCLUDE_DIR})
target_link_libraries(pcap_lib INTERFACE ${PCAP_LIBRARY})

add_library(geographiclib_lib INTERFACE)
target_include_directories(geographiclib_lib SYSTEM INTERFACE ${GeographicLib_INCLUDE_DIRS})
target_link_libraries(geographiclib_lib INTERFACE ${GeographicLib_LIBRARIES})

if(CONICLOC_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(CONICLOC_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

# Bag readers (io/): chunk decompression and ROS 2 .db3 storage, from Debian's -dev packages.
find_package(PkgConfig REQUIRED)
pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)
pkg_check_modules(LZ4 REQUIRED IMPORTED_TARGET liblz4)
pkg_check_modules(SQLITE3 REQUIRED IMPORTED_TARGET sqlite3)
find_package(BZip2 REQUIRED)
