-- `:SinumerikToolpath`: the toolpath of a buffer as the SVG of `sinumerik-lsp preview --format svg`,
-- written to a temporary file and opened with the system viewer (vim.ui.open on Neovim 0.10 and
-- newer, xdg-open or open before), or with the `viewer` function given to setup.
local M = {}

local function system_open(path)
  if vim.ui and vim.ui.open then
    return vim.ui.open(path)
  end
  local opener = vim.fn.has('mac') == 1 and 'open' or (vim.fn.has('win32') == 1 and 'explorer' or 'xdg-open')
  if vim.fn.executable(opener) ~= 1 then
    vim.notify('sinumerik: the toolpath is in ' .. path .. ' (no ' .. opener .. ' to open it)', vim.log.levels.WARN)
    return
  end
  vim.fn.jobstart({ opener, path }, { detach = true })
end

--- The command that previews `bufnr`. A buffer with unsaved changes is previewed from a copy of its
--- text in a temporary folder, with the configuration and called programs of the original folder.
function M.command(bufnr, binary, settings)
  local name = vim.api.nvim_buf_get_name(bufnr)
  local project = require('sinumerik.project')
  local args = { binary, 'preview', '--format', 'svg' }
  local config = project.config_file(name ~= '' and name or vim.fn.getcwd(), settings)
  if config then
    vim.list_extend(args, { '--config', config })
  end
  local file = name
  if name == '' or vim.bo[bufnr].modified or vim.fn.filereadable(name) ~= 1 then
    local folder = vim.fn.tempname()
    vim.fn.mkdir(folder, 'p')
    file = folder .. '/' .. (name ~= '' and vim.fn.fnamemodify(name, ':t') or 'PROGRAM.MPF')
    vim.fn.writefile(vim.api.nvim_buf_get_lines(bufnr, 0, -1, false), file)
    if name ~= '' then
      vim.list_extend(args, { '--cycles', vim.fn.fnamemodify(name, ':p:h') })
    end
  end
  table.insert(args, file)
  return args
end

--- Writes the SVG of `bufnr` and opens it. `done(path | nil, error)` is called when it is written
--- (for scripts and tests); `options.viewer(path)` replaces the system viewer.
function M.show(bufnr, options, done)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  local binary = options.cmd[1]
  local output = vim.fn.tempname() .. '.svg'
  local errors = {}
  local job = vim.fn.jobstart(M.command(bufnr, binary, options.settings), {
    stdout_buffered = true,
    stderr_buffered = true,
    on_stdout = function(_, data)
      vim.fn.writefile(data, output, 'b')
    end,
    on_stderr = function(_, data)
      errors = data
    end,
    on_exit = function(_, code)
      if code ~= 0 then
        local message = vim.trim(table.concat(errors, '\n'))
        vim.notify('sinumerik: the toolpath preview failed: ' .. message, vim.log.levels.ERROR)
        if done then
          done(nil, message)
        end
        return
      end
      local ok, problem = pcall(options.viewer or system_open, output)
      if not ok then
        vim.notify('sinumerik: the toolpath is in ' .. output .. ' (opening it failed: ' .. tostring(problem) .. ')', vim.log.levels.WARN)
      end
      if done then
        done(output, nil)
      end
    end,
  })
  if job <= 0 then
    local message = ('cannot run %s'):format(binary)
    vim.notify('sinumerik: ' .. message, vim.log.levels.ERROR)
    if done then
      done(nil, message)
    end
  end
end

return M
