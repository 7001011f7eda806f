# Generates the OpenGL 4.5 core and EGL 1.5 loaders with glad 2 (Debian python3-glad) at configure
# time, offline (--reproducible uses the specification bundled with the package).
find_program(GLAD_EXECUTABLE glad REQUIRED)
set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
set(GLAD_GL_EXTENSIONS GL_KHR_debug)
set(GLAD_EGL_EXTENSIONS
    EGL_EXT_platform_base,EGL_EXT_platform_device,EGL_EXT_device_base,EGL_EXT_device_enumeration,EGL_EXT_device_query,EGL_MESA_platform_surfaceless,EGL_KHR_surfaceless_context,EGL_KHR_create_context)
set(GLAD_STAMP "${GLAD_GL_EXTENSIONS};${GLAD_EGL_EXTENSIONS}")
if(NOT EXISTS ${GLAD_OUT}/src/gl.c OR NOT EXISTS ${GLAD_OUT}/src/egl.c OR NOT "${GLAD_STAMP}" STREQUAL "${SHADOWLAB_GLAD_STAMP}")
  message(STATUS "Generating glad loaders in ${GLAD_OUT}")
  execute_process(
    COMMAND ${GLAD_EXECUTABLE} --quiet --reproducible --api gl:core=4.5 --extensions ${GLAD_GL_EXTENSIONS}
            --out-path ${GLAD_OUT} c --loader
    RESULT_VARIABLE glad_gl_result)
  execute_process(
    COMMAND ${GLAD_EXECUTABLE} --quiet --reproducible --api egl=1.5 --extensions ${GLAD_EGL_EXTENSIONS}
            --out-path ${GLAD_OUT} c --loader
    RESULT_VARIABLE glad_egl_result)
  if(NOT glad_gl_result EQUAL 0 OR NOT glad_egl_result EQUAL 0)
    message(FATAL_ERROR "glad failed to generate the GL/EGL loaders")
  endif()
  set(SHADOWLAB_GLAD_STAMP "${GLAD_STAMP}" CACHE INTERNAL "")
endif()

# The host's loader (GL and EGL; libEGL is opened with dlopen by glad's internal loader, so the
# binary starts where no EGL is installed).
add_library(glad_host STATIC ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/src/egl.c)
target_include_directories(glad_host SYSTEM PUBLIC ${GLAD_OUT}/include)
target_link_libraries(glad_host PUBLIC ${CMAKE_DL_LIBS})

# Each plugin carries its own GL loader, filled from the host's proc-address function in init();
# hidden visibility keeps the plugin's copy private to it.
add_library(glad_plugin STATIC ${GLAD_OUT}/src/gl.c)
target_include_directories(glad_plugin SYSTEM PUBLIC ${GLAD_OUT}/include)
set_target_properties(glad_plugin PROPERTIES C_VISIBILITY_PRESET hidden)
