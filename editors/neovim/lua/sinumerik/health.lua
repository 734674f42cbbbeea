-- `:checkhealth sinumerik`: the server binary and its version, the machine configuration of the open
-- programs (found and accepted by the server's own reader), and whether the client is attached.
-- Neovim 0.7 reports through health#report_*, 0.8 and 0.9 through vim.health.report_*, 0.10 and
-- newer through vim.health.start/ok/warn/error.
local M = {}

local function reporter()
  local health = vim.health
  if health and health.start then
    return health
  end
  if health and health.report_start then
    return { start = health.report_start, ok = health.report_ok, warn = health.report_warn, error = health.report_error, info = health.report_info }
  end
  local function call(name)
    return function(message, advice)
      if advice then
        vim.fn['health#report_' .. name](message, advice)
      else
        vim.fn['health#report_' .. name](message)
      end
    end
  end
  return { start = call('start'), ok = call('ok'), warn = call('warn'), error = call('error'), info = call('info') }
end

--- Checks `config` with the server's reader: `check --config FILE` of a one-block program. Returns
--- true, or false and the server's message (exit code 2 is a configuration or usage error).
function M.validate_config(binary, config)
  local folder = vim.fn.tempname()
  vim.fn.mkdir(folder, 'p')
  local program = folder .. '/HEALTH.MPF'
  vim.fn.writefile({ 'N10 M30' }, program)
  local output = vim.fn.system({ binary, 'check', '--config', config, program })
  local code = vim.v.shell_error
  vim.fn.delete(folder, 'rf')
  if code == 2 then
    return false, vim.trim(output)
  end
  return true
end

function M.check()
  local report = reporter()
  local sinumerik = require('sinumerik')
  local project = require('sinumerik.project')
  local binary = sinumerik.options.cmd[1]

  report.start('sinumerik: language server')
  local path = vim.fn.exepath(binary)
  if path == '' then
    report.error(('the server "%s" is not executable or not on PATH'):format(binary), {
      'Install it with `cargo install --locked --path .` in the sinumerik-lsp repository',
      'or give its path: require("sinumerik").setup({ cmd = { "/path/to/sinumerik-lsp", "serve" } })',
    })
    return
  end
  local version = vim.trim(vim.fn.system({ path, '--version' }))
  if vim.v.shell_error ~= 0 or not version:match('^sinumerik%-lsp ') then
    report.error(('%s does not answer --version like sinumerik-lsp: %s'):format(path, version))
    return
  end
  report.ok(('%s found: %s'):format(version, path))

  report.start('sinumerik: machine configuration')
  local buffers = project.buffers()
  local places = {}
  for _, buf in ipairs(buffers) do
    local name = vim.api.nvim_buf_get_name(buf)
    table.insert(places, name ~= '' and name or vim.fn.getcwd())
  end
  if #places == 0 then
    table.insert(places, vim.fn.getcwd())
  end
  local seen = {}
  for _, place in ipairs(places) do
    local config = project.config_file(place, sinumerik.options.settings)
    if not config then
      if not seen[''] then
        seen[''] = true
        report.info(('no sinumerik.toml for %s: the server uses the setting machineKind (%s)'):format(
          place, sinumerik.options.settings.machineKind or 'mill'))
      end
    elseif not seen[config] then
      seen[config] = true
      if vim.fn.filereadable(config) ~= 1 then
        report.error(('configuration file %s cannot be read'):format(config))
      else
        local valid, problem = M.validate_config(path, config)
        if valid then
          report.ok(('configuration file %s is valid'):format(config))
        else
          report.error(('configuration file %s is not valid: %s'):format(config, problem), {
            'See docs/configuration.md of sinumerik-lsp for the keys and values',
          })
        end
      end
    end
  end

  report.start('sinumerik: LSP client')
  if #buffers == 0 then
    report.info('no SINUMERIK buffer is open: open a .mpf or .spf program to start the server')
    return
  end
  for _, buf in ipairs(buffers) do
    local name = vim.fn.fnamemodify(vim.api.nvim_buf_get_name(buf), ':t')
    local client = sinumerik.client(buf)
    if client then
      report.ok(('LSP client attached to %s (client id %d)'):format(name, client.id))
    else
      report.warn(('no LSP client attached to %s'):format(name), {
        'Call require("sinumerik").setup() in your configuration, or see :help sinumerik-lspconfig',
      })
    end
  end
end

return M
