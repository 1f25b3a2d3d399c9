# The live view's page: web/src bundled by esbuild (web/build.mjs) into index.html, app.js and
# app.css in the build tree; npm installs the pinned dependencies (package-lock.json) first.
# Without Node.js (-DFLAGSIM_WEB=OFF) a stand-in page says how to get the real one.
# Included by client/CMakeLists.txt; defines flagsim_web_files, the files flagctl embeds.
option(FLAGSIM_WEB "Build the live view's page (needs node and npm)" ON)

if(NOT FLAGSIM_WEB)
  set(flagsim_web_files ${PROJECT_SOURCE_DIR}/client/gateway/no_page/index.html)
  return()
endif()

find_program(FLAGSIM_NODE node)
find_program(FLAGSIM_NPM npm)
if(NOT FLAGSIM_NODE OR NOT FLAGSIM_NPM)
  message(FATAL_ERROR "the live view's page needs node and npm (scripts/install-deps.sh installs them); "
                      "configure with -DFLAGSIM_WEB=OFF to build flagctl without it")
endif()

set(web_dir ${PROJECT_SOURCE_DIR}/web)
set(web_out ${CMAKE_BINARY_DIR}/web)
set(web_sources
  ${web_dir}/build.mjs
  ${web_dir}/index.html
  ${web_dir}/style.css
  ${web_dir}/src/beside_view.js
  ${web_dir}/src/call_coalescer.js
  ${web_dir}/src/camera_controls.js
  ${web_dir}/src/camera_math.js
  ${web_dir}/src/camera_panel.js
  ${web_dir}/src/clock_controls.js
  ${web_dir}/src/clock_state.js
  ${web_dir}/src/connection.js
  ${web_dir}/src/design_panel.js
  ${web_dir}/src/design_upload.js
  ${web_dir}/src/dom.js
  ${web_dir}/src/frame_image.js
  ${web_dir}/src/frame_view.js
  ${web_dir}/src/main.js
  ${web_dir}/src/param_panel.js
  ${web_dir}/src/param_row.js
  ${web_dir}/src/param_slider.js
  ${web_dir}/src/params_table.js
  ${web_dir}/src/picture_stream.js
  ${web_dir}/src/plots.js
  ${web_dir}/src/server_list.js
  ${web_dir}/src/server_panel.js
  ${web_dir}/src/server_scope.js
  ${web_dir}/src/server_watch.js
  ${web_dir}/src/session_tools.js
  ${web_dir}/src/status_bar.js
  ${web_dir}/src/test_hooks.js
  ${web_dir}/src/tile_decoder.js
  ${web_dir}/src/timeline_model.js
  ${web_dir}/src/timeline_panel.js
  ${web_dir}/src/toast.js
  ${web_dir}/src/view_link.js
  ${web_dir}/src/wind_dial.js
  ${web_dir}/src/wind_form.js
  ${web_dir}/src/wind_panel.js)

# The locked dependencies into web/node_modules (git-ignored), again whenever the lock changes.
# --ignore-scripts: esbuild's binary comes as a package of its own; no install script is needed.
set(web_installed ${web_dir}/node_modules/.package-lock.json)
add_custom_command(
  OUTPUT ${web_installed}
  COMMAND ${FLAGSIM_NPM} ci --ignore-scripts --no-audit --no-fund --loglevel=error
  COMMAND ${CMAKE_COMMAND} -E touch ${web_installed}
  WORKING_DIRECTORY ${web_dir}
  DEPENDS ${web_dir}/package.json ${web_dir}/package-lock.json
  COMMENT "Installing the live view's dependencies (npm ci)"
  VERBATIM)

set(flagsim_web_files ${web_out}/index.html ${web_out}/app.js ${web_out}/app.css)
add_custom_command(
  OUTPUT ${flagsim_web_files}
  COMMAND ${FLAGSIM_NODE} ${web_dir}/build.mjs ${web_out}
  DEPENDS ${web_sources} ${web_installed}
  COMMENT "Building the live view's page (esbuild)"
  VERBATIM)

