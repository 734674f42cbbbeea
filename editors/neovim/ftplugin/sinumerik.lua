-- Buffer options for SINUMERIK NC programs: `;` starts a comment; words run together, so `$` and
-- `_` belong to names.
vim.bo.commentstring = '; %s'
vim.bo.comments = ':;'
vim.opt_local.iskeyword:append({ '$' })
