-- Headless end-to-end test of the Neovim plugin against the real server (Neovim 0.7 or newer):
--   SINUMERIK_LSP_BIN=target/release/sinumerik-lsp nvim --headless -u NONE -i NONE -n \
--     --cmd 'set rtp+=editors/neovim' -c 'luafile editors/neovim/test/e2e.lua'
-- It opens the turning seed example, waits for diagnostics, hovers on Z=IC(-32) and finds 58, edits
-- a line and sees the diagnostics change, runs :SinumerikPreview, changes a setting, renumbers and
-- formats scratch buffers with :SinumerikRenumber and :SinumerikFormat, goes to definitions and asks
-- for completions, and ends with `N passed, N failed` and a non-zero exit code on failure. No buffer
-- is ever written.
local passed, failed = 0, 0

local function report(ok, name, detail)
  if ok then
    passed = passed + 1
    io.stdout:write('ok     ' .. name .. '\n')
  else
    failed = failed + 1
    io.stdout:write('FAILED ' .. name .. (detail and (': ' .. detail) or '') .. '\n')
  end
end

local function check(name, fn)
  local ok, result, detail = pcall(fn)
  if not ok then
    report(false, name, tostring(result))
  else
    report(result, name, detail)
  end
end

local repository = vim.fn.fnamemodify(debug.getinfo(1, 'S').source:sub(2), ':p:h:h:h:h')
local binary = os.getenv('SINUMERIK_LSP_BIN') or (repository .. '/target/release/sinumerik-lsp')
local program = repository .. '/fixtures/examples/turning_seed.mpf'

-- Counts publishDiagnostics notifications for the program, so that the test can wait for the next one.
local published = 0
local default_handler = vim.lsp.handlers['textDocument/publishDiagnostics']
vim.lsp.handlers['textDocument/publishDiagnostics'] = function(err, result, ctx, config)
  default_handler(err, result, ctx, config)
  if result and result.uri == vim.uri_from_fname(program) then
    published = published + 1
  end
end

local function run()
  vim.cmd('filetype on')
  vim.cmd('filetype plugin on')
  vim.cmd('syntax on')
  if vim.fn.executable(binary) ~= 1 then
    report(false, 'the server binary exists', binary .. ' is not executable (build it with cargo build --release)')
    return
  end
  require('sinumerik').setup({ cmd = { binary, 'serve' }, settings = { inlayHints = 'all' } })
  vim.cmd('edit ' .. vim.fn.fnameescape(program))
  local buf = vim.api.nvim_get_current_buf()

  check('the .mpf file has filetype sinumerik', function()
    return vim.bo[buf].filetype == 'sinumerik', 'filetype is ' .. vim.bo[buf].filetype
  end)
  check('the program is highlighted: block number, axis, modifier, G code, comment', function()
    vim.cmd('syntax on')
    local function group(line, column)
      return vim.fn.synIDattr(vim.fn.synID(line, column, 1), 'name')
    end
    -- Line 4 is "N20 X75 Z=IC(-32)    ; X stays absolute, ...", line 2 starts "N5 G95".
    local seen = { group(4, 1), group(4, 5), group(4, 11), group(4, 22), group(2, 4) }
    local expected = { 'sinumerikBlockNumber', 'sinumerikAxis', 'sinumerikModifier', 'sinumerikComment', 'sinumerikGCode' }
    return vim.deep_equal(seen, expected), table.concat(seen, ' ')
  end)
  check('comments start with ;', function()
    return vim.bo[buf].commentstring == '; %s', vim.bo[buf].commentstring
  end)

  check('the server attaches to the buffer', function()
    return vim.wait(15000, function()
      return require('sinumerik').client(buf) ~= nil
    end, 20), 'no client after 15 s'
  end)
  check('diagnostics arrive for the opened program (it has none)', function()
    local arrived = vim.wait(15000, function()
      return published > 0
    end, 20)
    return arrived and #vim.diagnostic.get(buf) == 0, arrived and vim.inspect(vim.diagnostic.get(buf)) or 'none published'
  end)

  check('hover on Z=IC(-32) says the end point Z58', function()
    local line = 3 -- 0-based: "N20 X75 Z=IC(-32)    ; X stays absolute, ..."
    local text = vim.api.nvim_buf_get_lines(buf, line, line + 1, false)[1]
    local column = text:find('Z=IC', 1, true) - 1
    local params = { textDocument = { uri = vim.uri_from_bufnr(buf) }, position = { line = line, character = column } }
    local answers = vim.lsp.buf_request_sync(buf, 'textDocument/hover', params, 10000) or {}
    local contents = {}
    for _, answer in pairs(answers) do
      if answer.result and answer.result.contents then
        local value = answer.result.contents
        table.insert(contents, type(value) == 'table' and (value.value or vim.inspect(value)) or tostring(value))
      end
    end
    local hover = table.concat(contents, '\n')
    return hover:find('58', 1, true) ~= nil, 'hover was: ' .. hover
  end)

  check('an edit that breaks a modifier brings its diagnostic, undoing it clears it', function()
    local before = published
    vim.api.nvim_buf_set_lines(buf, 3, 4, false, { 'N20 X75 Z=IC -32' })
    local appeared = vim.wait(15000, function()
      for _, diagnostic in ipairs(vim.diagnostic.get(buf)) do
        if diagnostic.lnum == 3 and tostring(diagnostic.code) == 'S101' then
          return true
        end
      end
      return false
    end, 20)
    if not appeared then
      return false, 'no S101 on line 4 after the edit: ' .. vim.inspect(vim.diagnostic.get(buf))
    end
    vim.api.nvim_buf_set_lines(buf, 3, 4, false, { 'N20 X75 Z=IC(-32)    ; X stays absolute, Z incremental for this block only' })
    local cleared = vim.wait(15000, function()
      return published > before + 1 and #vim.diagnostic.get(buf) == 0
    end, 20)
    return cleared, 'still: ' .. vim.inspect(vim.diagnostic.get(buf))
  end)

  check(':SinumerikPreview lists the block end points in the quickfix list', function()
    local count, problem
    local original = require('sinumerik').preview
    -- The command's own path, with a hook to learn when the answer came.
    require('sinumerik').preview = function(bufnr)
      original(bufnr, function(n, err)
        count, problem = n, err
      end)
    end
    vim.cmd('SinumerikPreview')
    require('sinumerik').preview = original
    local done = vim.wait(15000, function()
      return count ~= nil or problem ~= nil
    end, 20)
    if not done or problem then
      return false, problem or 'no answer'
    end
    local list = vim.fn.getqflist()
    local texts = {}
    for _, item in ipairs(list) do
      table.insert(texts, item.lnum .. ': ' .. item.text)
    end
    local joined = table.concat(texts, '\n')
    local expected = {
      '3: N10 G1 -> X20 Z90 F0.2',
      '4: N20 G1 -> X75 Z58 F0.2',
      '5: N180 G1 -> X115 Z60 F0.2',
      '6: N190 G1 -> X103 Z17 F0.2',
    }
    if #list ~= #expected then
      return false, #list .. ' items:\n' .. joined
    end
    for index, line in ipairs(expected) do
      if texts[index] ~= line then
        return false, 'item ' .. index .. ' is "' .. texts[index] .. '", expected "' .. line .. '"'
      end
    end
    return vim.fn.getqflist({ title = 1 }).title == 'SINUMERIK end points: turning_seed.mpf', joined
  end)

  check('a quickfix item jumps to its line', function()
    vim.cmd('cc 2')
    return vim.api.nvim_get_current_buf() == buf and vim.api.nvim_win_get_cursor(0)[1] == 4,
      'cursor at ' .. vim.inspect(vim.api.nvim_win_get_cursor(0))
  end)

  local function inlay_hint_count()
    local params = {
      textDocument = { uri = vim.uri_from_bufnr(buf) },
      range = { start = { line = 0, character = 0 }, ['end'] = { line = 10, character = 0 } },
    }
    local count = 0
    for _, answer in pairs(vim.lsp.buf_request_sync(buf, 'textDocument/inlayHint', params, 10000) or {}) do
      count = count + #(answer.result or {})
    end
    return count
  end

  check('the settings reach the server, and a change takes effect without a restart', function()
    local all = inlay_hint_count()
    if all < 4 then
      return false, all .. ' inlay hints with inlayHints = all'
    end
    local id = require('sinumerik').client(buf).id
    require('sinumerik').update_settings({ inlayHints = 'off' })
    local off = all
    vim.wait(10000, function()
      off = inlay_hint_count()
      return off == 0
    end, 50)
    local client = require('sinumerik').client(buf)
    return off == 0 and client.id == id, off .. ' hints after inlayHints = off (client ' .. client.id .. ', was ' .. id .. ')'
  end)

  -- The commands that rewrite a program run on scratch buffers that are never written.
  local folder = vim.fn.tempname()
  vim.fn.mkdir(folder, 'p')
  local function scratch(name, lines)
    vim.cmd('hide edit ' .. vim.fn.fnameescape(folder .. '/' .. name))
    local bufnr = vim.api.nvim_get_current_buf()
    vim.api.nvim_buf_set_lines(bufnr, 0, -1, false, lines)
    -- Closes the undo step of the text, as a user's next command would.
    vim.cmd('let &undolevels = &undolevels')
    local attached = vim.wait(15000, function()
      return require('sinumerik').client(bufnr) ~= nil
    end, 20)
    return bufnr, attached
  end

  -- Runs the user command `command` and waits for the answer, through a hook on `M[name]`.
  local function run_command(name, command)
    local module = require('sinumerik')
    local original = module[name]
    local result, problem
    module[name] = function(...)
      local args = { ... }
      table.insert(args, function(value, err)
        result, problem = value, err
      end)
      original(unpack(args))
    end
    local ok, error = pcall(vim.cmd, command)
    module[name] = original
    if not ok then
      return nil, tostring(error)
    end
    if not vim.wait(15000, function()
      return result ~= nil or problem ~= nil
    end, 20) then
      return nil, 'no answer'
    end
    return result, problem
  end

  check(':SinumerikRenumber reads start, step and mode, and refuses what is not a block number', function()
    local sinumerik = require('sinumerik')
    local cases = {
      { {}, { start = 10, step = 10, mode = 'keep' } },
      { { '100', '5', 'all' }, { start = 100, step = 5, mode = 'all' } },
      { { 'drop' }, { start = 10, step = 10, mode = 'drop' } },
      { { '0', 'drop', '1' }, { start = 0, step = 1, mode = 'drop' } },
    }
    for _, case in ipairs(cases) do
      local options, problem = sinumerik.renumber_options(case[1])
      if not vim.deep_equal(options, case[2]) then
        return false, table.concat(case[1], ' ') .. ' gave ' .. vim.inspect(options) .. ' ' .. tostring(problem)
      end
    end
    local completed = vim.fn.getcompletion('SinumerikRenumber 10 d', 'cmdline')
    if not vim.deep_equal(completed, { 'drop' }) then
      return false, 'completion of "d": ' .. vim.inspect(completed)
    end
    for _, bad in ipairs({ { '10', '0' }, { 'ten' }, { '-5' }, { '1', '2', '3' }, { '2147483648' }, { 'KEEP' } }) do
      local options, problem = sinumerik.renumber_options(bad)
      if options ~= nil or type(problem) ~= 'string' then
        return false, table.concat(bad, ' ') .. ' was accepted'
      end
    end
    return true
  end)

  check(':SinumerikRenumber 100 5 all renumbers the buffer, jumps included', function()
    local bufnr, attached = scratch('renumber.mpf', {
      'N1 G90 G71 G17 G0 X0 Y0',
      'N2 IF R1 > 0 GOTOF N9',
      'N3 G1 X10 F100',
      'N9 G0 X20',
      'M30',
    })
    if not attached then
      return false, 'no client for the scratch buffer'
    end
    local result, problem = run_command('renumber', 'SinumerikRenumber 100 5 all')
    if problem then
      return false, problem
    end
    local lines = vim.api.nvim_buf_get_lines(bufnr, 0, -1, false)
    local expected = { 'N100 G90 G71 G17 G0 X0 Y0', 'N105 IF R1 > 0 GOTOF N115', 'N110 G1 X10 F100', 'N115 G0 X20', 'N120 M30' }
    return vim.deep_equal(lines, expected) and result.applied == true, table.concat(lines, ' | ') .. ' ' .. vim.inspect(result)
  end)

  check(':SinumerikRenumber shows the refusal of the server', function()
    local bufnr = vim.api.nvim_get_current_buf()
    local before = vim.api.nvim_buf_get_lines(bufnr, 0, -1, false)
    local refused, problem
    require('sinumerik').renumber(bufnr, { start = 10, step = 0, mode = 'keep' }, function(value, err)
      refused, problem = value, err
    end)
    vim.wait(15000, function()
      return refused ~= nil or problem ~= nil
    end, 20)
    local after = vim.api.nvim_buf_get_lines(bufnr, 0, -1, false)
    return refused == nil and type(problem) == 'string' and problem:find('step', 1, true) ~= nil and vim.deep_equal(before, after),
      'answer ' .. vim.inspect(refused) .. ', error ' .. tostring(problem)
  end)

  check(':SinumerikFormat normalises spacing and case, and one undo takes it back', function()
    local bufnr, attached = scratch('format.mpf', { 'n10 g0x10  y5', 'N20 g1 x=ic( 5 ) f100', 'm30' })
    if not attached then
      return false, 'no client for the scratch buffer'
    end
    local result, problem = run_command('format', 'SinumerikFormat')
    if problem then
      return false, problem
    end
    local lines = vim.api.nvim_buf_get_lines(bufnr, 0, -1, false)
    if not (vim.deep_equal(lines, { 'N10 G0 X10 Y5', 'N20 G1 X=IC(5) F100', 'M30' }) and result.applied == true) then
      return false, table.concat(lines, ' | ') .. ' ' .. vim.inspect(result)
    end
    -- The whole edit is one undo step.
    vim.cmd('undo')
    local undone = vim.api.nvim_buf_get_lines(bufnr, 0, -1, false)
    return vim.deep_equal(undone, { 'n10 g0x10  y5', 'N20 g1 x=ic( 5 ) f100', 'm30' }), 'after one undo: ' .. table.concat(undone, ' | ')
  end)

  -- The program both editors' tests navigate: line 4 (0-based) jumps forward to FINISH on line 7,
  -- line 6 backward to START on line 1; DEPTH is declared on line 0 and used on line 5.
  local navigation = vim.fn.readfile(repository .. '/fixtures/editors/navigation.mpf')
  local nav, nav_attached = scratch('navigation.mpf', navigation)

  local function request(method, line, character)
    local params = { textDocument = { uri = vim.uri_from_bufnr(nav) }, position = { line = line, character = character } }
    local results = {}
    for _, answer in pairs(vim.lsp.buf_request_sync(nav, method, params, 10000) or {}) do
      if answer.err then
        error(method .. ': ' .. vim.inspect(answer.err))
      end
      table.insert(results, answer.result)
    end
    return results[1]
  end

  check('go to definition (gd with vim.lsp.buf.definition) finds the label and the DEF', function()
    if not nav_attached then
      return false, 'no client for the scratch buffer'
    end
    local function target_line(line, word)
      local answer = request('textDocument/definition', line, navigation[line + 1]:find(word, 1, true))
      if answer and answer[1] then
        answer = answer[1]
      end
      local range = answer and (answer.targetSelectionRange or answer.range)
      return range and range.start.line
    end
    local found = { target_line(4, 'FINISH'), target_line(6, 'START'), target_line(5, 'DEPTH') }
    return vim.deep_equal(found, { 7, 1, 0 }), vim.inspect(found)
  end)

  check('completion (omnifunc) offers the labels a jump reaches and G functions with their group', function()
    local function labels(answer)
      local items = answer and (answer.items or answer) or {}
      local names = {}
      for _, item in ipairs(items) do
        table.insert(names, item.label)
      end
      return names, items
    end
    local forward = labels(request('textDocument/completion', 4, #'N20 IF R1 > 0 GOTOF '))
    local backward = labels(request('textDocument/completion', 6, #'N40 IF R2 > 0 GOTOB '))
    local _, g_items = labels(request('textDocument/completion', 5, #'N30 G1'))
    local g17
    for _, item in ipairs(g_items) do
      if item.label == 'G17' then
        g17 = item
      end
    end
    local ok = vim.deep_equal(forward, { 'FINISH' }) and vim.deep_equal(backward, { 'START' })
      and g17 ~= nil and (g17.detail or ''):find('group 6', 1, true) ~= nil
      and vim.bo[nav].omnifunc == 'v:lua.vim.lsp.omnifunc'
    return ok, vim.inspect({ forward = forward, backward = backward, g17 = g17, omnifunc = vim.bo[nav].omnifunc })
  end)
end

local ok, problem = pcall(run)
if not ok then
  report(false, 'the test ran to its end', tostring(problem))
end
io.stdout:write(string.format('%d passed, %d failed\n', passed, failed))
io.stdout:flush()
for _, client in pairs(vim.lsp.get_active_clients()) do
  client.stop(true)
end
if failed > 0 then
  vim.cmd('cquit 1')
else
  vim.cmd('qall!')
end
