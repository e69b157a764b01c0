# qverify_add_room(NAME SOURCES src... LINKS target...)
# The library of the room NAME/ (one job, one folder): the static library qverify_NAME, alias
# qverify::NAME, exported as NAME; its headers are NAME/include/qverify/NAME/*.hpp, installed;
# it links publicly the rooms before it in the flow (scene -> eval -> verify -> studies -> report).
function(qverify_add_room name)
  cmake_parse_arguments(PARSE_ARGV 1 ROOM "" "" "SOURCES;LINKS")
  add_library(qverify_${name} STATIC ${ROOM_SOURCES})
  add_library(qverify::${name} ALIAS qverify_${name})
  set_target_properties(qverify_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(qverify_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(qverify_${name} PUBLIC ${ROOM_LINKS})
  target_compile_options(qverify_${name} PRIVATE -Wall -Wextra)
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
