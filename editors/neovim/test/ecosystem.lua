-- Headless test of the plugin's help, health check and toolpath command against the real server
-- (Neovim 0.7 or newer), run by run.sh after e2e.lua:
--   :help sinumerik and every |link| of doc/sinumerik.txt resolve (tags made here with :helptags, in a
--   copy of the help, so that the repository stays untouched);
--   :checkhealth sinumerik says OK for the binary and its version, a valid sinumerik.toml and the
--   attached client, and ERROR with the server's message for an invalid sinumerik.toml;
--   :SinumerikToolpath writes a well-formed SVG of the buffer (of its unsaved text too) and hands it
--   to the viewer, a stub here.
-- Ends with `N passed, N failed` and a non-zero exit code on failure. No buffer of the repository is
-- written.
local passed, failed = 0, 0

local function check(name, fn)
  local ok, result, detail = pcall(fn)
  if ok and result then
    passed = passed + 1
    io.stdout:write('ok     ' .. name .. '\n')
  else
    failed = failed + 1
    io.stdout:write('FAILED ' .. name .. ': ' .. tostring(ok and detail or result) .. '\n')
  end
end

local repository = vim.fn.fnamemodify(debug.getinfo(1, 'S').source:sub(2), ':p:h:h:h:h')
local binary = os.getenv('SINUMERIK_LSP_BIN') or (repository .. '/target/release/sinumerik-lsp')
local scratch = vim.fn.tempname()

--- A project folder in the scratch folder with a program and, when given, a sinumerik.toml.
local function project(name, toml)
  local folder = scratch .. '/' .. name
  vim.fn.mkdir(folder, 'p')
  vim.fn.writefile({ 'N10 G17 G90 G54 T1 D1 M6', 'N20 G0 X0 Y0 Z5', 'N30 G1 Z-2 F300', 'N40 X40 Y=IC(10)', 'N50 G2 X60 Y30 CR=20', 'N60 M30' },
    folder .. '/PART.MPF')
  if toml then
    vim.fn.writefile(toml, folder .. '/sinumerik.toml')
  end
  return folder
end

--- The lines of `:checkhealth sinumerik`, its tab closed again.
local function checkhealth()
  vim.cmd('silent checkhealth sinumerik')
  local lines = vim.api.nvim_buf_get_lines(0, 0, -1, false)
  vim.cmd('tabclose')
  return lines
end

local function has_line(lines, ...)
  for _, line in ipairs(lines) do
    local all = true
    for _, part in ipairs({ ... }) do
      all = all and line:find(part, 1, true) ~= nil
    end
    if all then
      return true
    end
  end
  return false
end

local function run()
  vim.cmd('filetype plugin on')
  vim.fn.mkdir(scratch, 'p')

  local doc = scratch .. '/help/doc'
  vim.fn.mkdir(doc, 'p')
  vim.fn.writefile(vim.fn.readfile(repository .. '/editors/neovim/doc/sinumerik.txt'), doc .. '/sinumerik.txt')
  vim.cmd('helptags ' .. vim.fn.fnameescape(doc))
  vim.opt.runtimepath:prepend(scratch .. '/help')

  check(':help sinumerik opens the plugin help at its tag', function()
    vim.cmd('help sinumerik')
    local name = vim.api.nvim_buf_get_name(0)
    local line = vim.api.nvim_get_current_line()
    vim.cmd('helpclose')
    return name:match('sinumerik%.txt$') ~= nil and line:find('*sinumerik*', 1, true) ~= nil, name .. ': ' .. line
  end)
  check('every |link| of the help resolves to a tag', function()
    local text = table.concat(vim.fn.readfile(doc .. '/sinumerik.txt'), '\n')
    local broken, count = {}, 0
    for tag in text:gmatch('|([^|%s]+)|') do
      count = count + 1
      if not pcall(vim.cmd, 'help ' .. tag) then
        table.insert(broken, tag)
      end
    end
    vim.cmd('helpclose')
    return count >= 10 and #broken == 0, ('%d links, broken: %s'):format(count, table.concat(broken, ' '))
  end)
  check('the commands, settings, mappings and lspconfig setup have help tags', function()
    local missing = {}
    for _, tag in ipairs({ ':SinumerikToolpath', ':SinumerikPreview', ':SinumerikRenumber', ':SinumerikFormat',
      'sinumerik-settings', 'sinumerik-mappings', 'sinumerik-health', 'sinumerik-lspconfig' }) do
      if not pcall(vim.cmd, 'help ' .. tag) then
        table.insert(missing, tag)
      end
    end
    vim.cmd('helpclose')
    return #missing == 0, 'missing: ' .. table.concat(missing, ' ')
  end)

  if vim.fn.executable(binary) ~= 1 then
    check('the server binary exists', function()
      return false, binary .. ' is not executable (build it with cargo build --release)'
    end)
    return
  end
  local opened = {}
  require('sinumerik').setup({ cmd = { binary, 'serve' }, viewer = function(path)
    table.insert(opened, path)
  end })

  local good = project('good', { '[machine]', 'kind = "mill"', 'max_skip_level = 7' })
  vim.cmd('edit ' .. vim.fn.fnameescape(good .. '/PART.MPF'))
  local part = vim.api.nvim_get_current_buf()
  local attached = vim.wait(15000, function()
    return require('sinumerik').client(part) ~= nil
  end, 20)

  check(':checkhealth sinumerik says OK for the binary, the configuration and the client', function()
    local lines = checkhealth()
    local version = vim.trim(vim.fn.system({ binary, '--version' }))
    local ok = attached and has_line(lines, 'OK', version, 'found')
      and has_line(lines, 'OK', 'configuration file', good .. '/sinumerik.toml', 'is valid')
      and has_line(lines, 'OK', 'LSP client attached to PART.MPF')
      and not has_line(lines, 'ERROR')
    return ok, table.concat(lines, '\n')
  end)

  check(':checkhealth sinumerik shows the server\'s message for an invalid sinumerik.toml', function()
    local bad = project('bad', { '[machine]', 'kind = "lathe"' })
    vim.cmd('edit ' .. vim.fn.fnameescape(bad .. '/PART.MPF'))
    local lines = checkhealth()
    vim.cmd('bwipeout!')
    local ok = has_line(lines, 'ERROR', bad .. '/sinumerik.toml', 'is not valid', 'lathe')
      and has_line(lines, 'OK', good .. '/sinumerik.toml', 'is valid')
    return ok, table.concat(lines, '\n')
  end)

  local function toolpath()
    local path, problem
    require('sinumerik').toolpath(part, function(p, e)
      path, problem = p, e
    end)
    vim.wait(15000, function()
      return path ~= nil or problem ~= nil
    end, 20)
    return path, problem
  end

  local function svg_check(path)
    local script = 'import sys, xml.etree.ElementTree as E\n'
      .. 'root = E.parse(sys.argv[1]).getroot()\n'
      .. 'titles = [t.text for t in root.iter("{http://www.w3.org/2000/svg}title")]\n'
      .. 'print(root.tag, *titles, sep="|")'
    return vim.trim(vim.fn.system({ 'python3', '-c', script, path })), vim.v.shell_error
  end

  check(':SinumerikToolpath writes a well-formed SVG of the program and opens it with the viewer', function()
    vim.cmd('buffer ' .. part)
    local path, problem = toolpath()
    if not path then
      return false, 'no SVG: ' .. tostring(problem)
    end
    local parsed, code = svg_check(path)
    local ok = code == 0 and opened[#opened] == path and parsed:match('^{http://www.w3.org/2000/svg}svg|') ~= nil
      and parsed:find('|line 5', 1, true) ~= nil and parsed:find('|line 7', 1, true) == nil
    return ok, ('%s -> %s (viewer got %s)'):format(path, parsed, tostring(opened[#opened]))
  end)

  check(':SinumerikToolpath draws the unsaved text of the buffer', function()
    vim.api.nvim_buf_set_lines(part, 5, 5, false, { 'N55 G1 X0 Y0' })
    local path, problem = toolpath()
    local on_disk = vim.fn.readfile(good .. '/PART.MPF')
    if not path then
      return false, 'no SVG: ' .. tostring(problem)
    end
    local parsed, code = svg_check(path)
    return code == 0 and #on_disk == 6 and parsed:find('|line 6', 1, true) ~= nil, parsed
  end)

  check('the command :SinumerikToolpath exists after setup', function()
    return vim.fn.exists(':SinumerikToolpath') == 2, 'exists() = ' .. vim.fn.exists(':SinumerikToolpath')
  end)
end

local ok, problem = pcall(run)
if not ok then
  failed = failed + 1
  io.stdout:write('FAILED the test ran to its end: ' .. tostring(problem) .. '\n')
end
io.stdout:write(string.format('%d passed, %d failed\n', passed, failed))
io.stdout:flush()
for _, client in pairs(vim.lsp.get_active_clients()) do
  client.stop(true)
end
vim.fn.delete(scratch, 'rf')
if failed > 0 then
  vim.cmd('cquit 1')
else
  vim.cmd('qall!')
end
