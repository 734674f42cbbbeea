-- Where a SINUMERIK buffer's machine configuration comes from, as the server finds it: the setting
-- `configFile` when set, else the nearest `sinumerik.toml` in the program's folder or a folder above.
local M = {}

--- The `sinumerik.toml` that applies to `path` (a file or folder), or nil when the defaults apply.
function M.config_file(path, settings)
  if settings and type(settings.configFile) == 'string' and settings.configFile ~= '' then
    return vim.fn.fnamemodify(settings.configFile, ':p')
  end
  local folder = vim.fn.isdirectory(path) == 1 and path or vim.fn.fnamemodify(path, ':p:h')
  local found = vim.fn.findfile('sinumerik.toml', folder .. ';')
  return found ~= '' and vim.fn.fnamemodify(found, ':p') or nil
end

--- The loaded buffers of filetype `sinumerik`.
function M.buffers()
  return vim.tbl_filter(function(buf)
    return vim.api.nvim_buf_is_loaded(buf) and vim.bo[buf].filetype == 'sinumerik'
  end, vim.api.nvim_list_bufs())
end

return M
