-- The SINUMERIK language server in Neovim: starts `sinumerik-lsp serve` for buffers of filetype
-- `sinumerik` (vim.lsp.start where it exists, vim.lsp.start_client on Neovim 0.7), passes the
-- settings, lists the resolved block end points in the quickfix list (:SinumerikPreview), shows the
-- toolpath as SVG (:SinumerikToolpath, in toolpath.lua), and renumbers and formats programs with the
-- server's commands (:SinumerikRenumber, :SinumerikFormat). `:checkhealth sinumerik` is health.lua.
local M = {}

local PREVIEW_COMMAND = 'sinumerik.endpointPreview'
local RENUMBER_COMMAND = 'sinumerik.renumber'
local FORMAT_COMMAND = 'sinumerik.format'
-- The largest block number the server writes (a signed 32-bit integer, like other NC integers).
local MAX_BLOCK_NUMBER = 2147483647
M.NUMBERING_MODES = { 'keep', 'all', 'drop' }

local defaults = {
  -- The server command; the binary must be on PATH unless a full path is given.
  cmd = { 'sinumerik-lsp', 'serve' },
  -- The `sinumerik` settings section (see docs/server.md, Settings): inlayHints, machineKind, configFile,
  -- maxDiagnostics (0: every finding; Neovim shows them all).
  settings = {
    inlayHints = 'notPlain',
    machineKind = 'mill',
    configFile = '',
    maxDiagnostics = 0,
  },
  -- Files that mark a project's root; the folder of the file when none is found.
  root_markers = { 'sinumerik.toml', '.git' },
  on_attach = nil,
  capabilities = nil,
  -- Opens the SVG of :SinumerikToolpath; nil: the system viewer (vim.ui.open, xdg-open, open).
  viewer = nil,
}

M.options = vim.deepcopy(defaults)
-- Neovim 0.7: one client per root folder, reused for every buffer below it.
local clients_by_root = {}

local function find_root(path)
  local folder = vim.fn.fnamemodify(path, ':p:h')
  for _, marker in ipairs(M.options.root_markers) do
    local file = vim.fn.findfile(marker, folder .. ';')
    if file ~= '' then
      return vim.fn.fnamemodify(file, ':p:h')
    end
    local dir = vim.fn.finddir(marker, folder .. ';')
    if dir ~= '' then
      -- ':p' of a folder ends in a slash: ':h' drops it, the second ':h' the marker itself.
      return vim.fn.fnamemodify(dir, ':p:h:h')
    end
  end
  return folder
end

local function client_config(root)
  return {
    name = 'sinumerik',
    cmd = M.options.cmd,
    root_dir = root,
    workspace_folders = { { uri = vim.uri_from_fname(root), name = root } },
    init_options = M.options.settings,
    -- Answered to workspace/configuration requests for the section `sinumerik`.
    settings = { sinumerik = M.options.settings },
    on_attach = M.options.on_attach,
    capabilities = M.options.capabilities,
  }
end

local function command_exists(cmd)
  return vim.fn.executable(cmd[1]) == 1
end

local warned = false
--- Starts (or reuses) the server for buffer `bufnr`.
function M.start(bufnr)
  bufnr = bufnr or vim.api.nvim_get_current_buf()
  if not command_exists(M.options.cmd) then
    if not warned then
      warned = true
      vim.notify(
        ('sinumerik: the language server "%s" was not found. Install it with `cargo install --path .` in the '
          .. 'sinumerik-lsp repository, or pass its path: require("sinumerik").setup({ cmd = { "/path/to/sinumerik-lsp", "serve" } })')
          :format(M.options.cmd[1]),
        vim.log.levels.ERROR
      )
    end
    return nil
  end
  local name = vim.api.nvim_buf_get_name(bufnr)
  local root = find_root(name ~= '' and name or vim.fn.getcwd() .. '/x')
  if vim.lsp.start then
    return vim.lsp.start(client_config(root), { bufnr = bufnr })
  end
  local id = clients_by_root[root]
  local client = id and vim.lsp.get_client_by_id(id)
  if not client or client.is_stopped() then
    id = vim.lsp.start_client(client_config(root))
    clients_by_root[root] = id
  end
  if id then
    vim.lsp.buf_attach_client(bufnr, id)
  end
  return id
end

--- The running sinumerik client attached to `bufnr`, if any.
function M.client(bufnr)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  local clients = vim.lsp.get_clients and vim.lsp.get_clients({ bufnr = bufnr }) or vim.lsp.buf_get_clients(bufnr)
  for _, client in pairs(clients) do
    if client.name == 'sinumerik' then
      return client
    end
  end
  return nil
end

--- Changes settings of the running servers without a restart.
function M.update_settings(settings)
  M.options.settings = vim.tbl_extend('force', M.options.settings, settings or {})
  local clients = vim.lsp.get_clients and vim.lsp.get_clients() or vim.lsp.get_active_clients()
  for _, client in pairs(clients) do
    if client.name == 'sinumerik' then
      client.config.settings = { sinumerik = M.options.settings }
      client.notify('workspace/didChangeConfiguration', { settings = { sinumerik = M.options.settings } })
    end
  end
end

local AXIS_ORDER = { X = 1, Y = 2, Z = 3, A = 4, B = 5, C = 6 }

local function number_text(value)
  local text = string.format('%.4f', value):gsub('0+$', ''):gsub('%.$', '')
  return text == '-0' and '0' or text
end

--- One quickfix line for a move of the preview: block, motion, end point, unknown axes.
function M.describe_move(move)
  local axes = {}
  for axis, value in pairs(move['end'] or {}) do
    table.insert(axes, { axis = axis, value = value })
  end
  table.sort(axes, function(a, b)
    local oa, ob = AXIS_ORDER[a.axis] or 99, AXIS_ORDER[b.axis] or 99
    if oa ~= ob then
      return oa < ob
    end
    return a.axis < b.axis
  end)
  local parts = {}
  if type(move.block) == 'string' then
    table.insert(parts, move.block)
  end
  table.insert(parts, move.motion)
  local point = {}
  for _, item in ipairs(axes) do
    table.insert(point, item.axis .. number_text(item.value))
  end
  table.insert(parts, '-> ' .. (#point > 0 and table.concat(point, ' ') or '(no known axis)'))
  if type(move.feed) == 'number' then
    table.insert(parts, 'F' .. number_text(move.feed))
  end
  local uncertain = move.uncertain
  if type(uncertain) == 'table' and #uncertain > 0 then
    table.insert(parts, '(uncertain: ' .. table.concat(uncertain, ' ') .. ')')
  end
  return table.concat(parts, ' ')
end

--- The sinumerik client of `bufnr`; without one, warns and calls `done(nil, 'no server')`.
local function client_or_warn(bufnr, done)
  local client = M.client(bufnr)
  if not client then
    vim.notify('sinumerik: no language server runs for this buffer', vim.log.levels.WARN)
    if done then
      done(nil, 'no server')
    end
  end
  return client
end

--- Fills the quickfix list with the end point of every block of `bufnr` that moves, and opens it.
--- `done(count | nil, error)` is called when the answer came (for scripts and tests).
function M.preview(bufnr, done)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  local client = client_or_warn(bufnr, done)
  if not client then
    return
  end
  local params = { command = PREVIEW_COMMAND, arguments = { { uri = vim.uri_from_bufnr(bufnr) } } }
  client.request('workspace/executeCommand', params, function(err, result)
    if err or type(result) ~= 'table' or type(result.moves) ~= 'table' then
      local message = err and (err.message or vim.inspect(err)) or 'the answer has no moves'
      vim.notify('sinumerik: the preview failed: ' .. message, vim.log.levels.ERROR)
      if done then
        done(nil, message)
      end
      return
    end
    local items = {}
    for _, move in ipairs(result.moves) do
      table.insert(items, { bufnr = bufnr, lnum = move.line, col = 1, text = M.describe_move(move) })
    end
    local title = 'SINUMERIK end points: ' .. vim.fn.fnamemodify(vim.api.nvim_buf_get_name(bufnr), ':t')
    vim.fn.setqflist({}, ' ', { title = title, items = items })
    vim.cmd('copen')
    if done then
      done(#items, nil)
    end
  end, bufnr)
end

--- Reads the arguments of `:SinumerikRenumber [start] [step] [keep|all|drop]`: the mode may stand
--- anywhere, the first number is the start and the second the step. Returns the options
--- `{ start, step, mode }` (defaults 10, 10, keep), or nil and the reason.
function M.renumber_options(args)
  local options = { start = 10, step = 10, mode = 'keep' }
  local numbers = {}
  for _, word in ipairs(args or {}) do
    if vim.tbl_contains(M.NUMBERING_MODES, word) then
      options.mode = word
    elseif word:match('^%d+$') then
      table.insert(numbers, tonumber(word))
    else
      return nil, ('"%s" is neither a block number nor keep, all or drop'):format(word)
    end
  end
  if #numbers > 2 then
    return nil, 'give at most a start and a step'
  end
  options.start = numbers[1] or options.start
  options.step = numbers[2] or options.step
  if options.step < 1 then
    return nil, 'the step must be at least 1'
  end
  if options.start > MAX_BLOCK_NUMBER or options.step > MAX_BLOCK_NUMBER then
    return nil, ('block numbers go up to %d'):format(MAX_BLOCK_NUMBER)
  end
  return options
end

--- What the user is told of the answer `{ applied, edits }` to `what`: the message and its level.
function M.describe_outcome(what, result)
  if type(result) ~= 'table' or type(result.applied) ~= 'boolean' or type(result.edits) ~= 'number' then
    return what .. ': the server gave an answer the plugin does not understand: ' .. vim.inspect(result), vim.log.levels.ERROR
  end
  if result.edits == 0 then
    return what .. ': nothing to change', vim.log.levels.INFO
  end
  if not result.applied then
    return what .. ': the edit was not applied (was the buffer changed meanwhile?)', vim.log.levels.ERROR
  end
  return ('%s: %d %s applied'):format(what, result.edits, result.edits == 1 and 'change' or 'changes'), vim.log.levels.INFO
end

--- Sends the server command `command` for `bufnr`; the server edits the buffer with
--- workspace/applyEdit, which Neovim's LSP client applies. `done(result | nil, error)` is called
--- when the answer came (for scripts and tests).
local function rewrite(bufnr, what, command, argument, done)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  local client = client_or_warn(bufnr, done)
  if not client then
    return
  end
  argument.uri = vim.uri_from_bufnr(bufnr)
  local params = { command = command, arguments = { argument } }
  client.request('workspace/executeCommand', params, function(err, result)
    if err then
      local message = err.message or vim.inspect(err)
      vim.notify('sinumerik: ' .. what .. ' failed: ' .. message, vim.log.levels.ERROR)
      if done then
        done(nil, message)
      end
      return
    end
    local message, level = M.describe_outcome(what, result)
    vim.notify('sinumerik: ' .. message, level)
    if done then
      done(result, level == vim.log.levels.ERROR and message or nil)
    end
  end, bufnr)
end

--- Renumbers the blocks of `bufnr` with `options` `{ start, step, mode }` (see renumber_options).
function M.renumber(bufnr, options, done)
  rewrite(bufnr, 'renumbering', RENUMBER_COMMAND, vim.deepcopy(options), done)
end

--- Formats `bufnr` with the server's `sinumerik.format` (the same edits as vim.lsp.buf.format()).
function M.format(bufnr, done)
  rewrite(bufnr, 'formatting', FORMAT_COMMAND, {}, done)
end

--- Writes the toolpath of `bufnr` as SVG (`sinumerik-lsp preview --format svg`) and opens it with the
--- viewer; `done(path | nil, error)` is called once the file is written (for scripts and tests).
function M.toolpath(bufnr, done)
  require('sinumerik.toolpath').show(bufnr, M.options, done)
end

--- The buffer-local commands of a SINUMERIK buffer, and completion with <C-x><C-o> from the server
--- (Neovim 0.7 does not set 'omnifunc' for LSP buffers itself; one set by the user stays).
function M.prepare_buffer(bufnr)
  if vim.bo[bufnr].omnifunc == '' then
    vim.bo[bufnr].omnifunc = 'v:lua.vim.lsp.omnifunc'
  end
  vim.api.nvim_buf_create_user_command(bufnr, 'SinumerikRenumber', function(command)
    local options, problem = M.renumber_options(command.fargs)
    if not options then
      vim.notify('sinumerik: :SinumerikRenumber [start] [step] [keep|all|drop]: ' .. problem, vim.log.levels.ERROR)
      return
    end
    M.renumber(0, options)
  end, {
    nargs = '*',
    -- Like customlist: Neovim does not filter what the function returns.
    complete = function(lead)
      return vim.tbl_filter(function(mode)
        return mode:sub(1, #lead) == lead
      end, M.NUMBERING_MODES)
    end,
    desc = 'Renumber the blocks: start (10), step (10), keep, all or drop existing numbers (keep)',
  })
  vim.api.nvim_buf_create_user_command(bufnr, 'SinumerikFormat', function()
    M.format(0)
  end, { desc = 'Normalise spacing and letter case without changing what a block means' })
end

function M.setup(options)
  M.options = vim.tbl_deep_extend('force', vim.deepcopy(defaults), options or {})
  local group = vim.api.nvim_create_augroup('sinumerik', { clear = true })
  vim.api.nvim_create_autocmd('FileType', {
    group = group,
    pattern = 'sinumerik',
    callback = function(args)
      M.prepare_buffer(args.buf)
      M.start(args.buf)
    end,
  })
  vim.api.nvim_create_user_command('SinumerikPreview', function()
    M.preview(0)
  end, { desc = 'List the resolved end point of every moving block in the quickfix list' })
  vim.api.nvim_create_user_command('SinumerikToolpath', function()
    M.toolpath(0)
  end, { desc = 'Write the toolpath as SVG and open it with the system viewer' })
  -- Buffers that were opened before setup.
  for _, buf in ipairs(vim.api.nvim_list_bufs()) do
    if vim.api.nvim_buf_is_loaded(buf) and vim.bo[buf].filetype == 'sinumerik' then
      M.prepare_buffer(buf)
      M.start(buf)
    end
  end
end

return M
